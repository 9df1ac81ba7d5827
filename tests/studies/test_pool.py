"""studies.pool: tasks started on a local process pool while the caller works on (compare's
strikes beside its nominal, then its band)."""

from formopt.studies.pool import Background


def test_background_tasks_keep_their_order():
    """Tasks on two processes and in this one: results in the tasks' order, each told."""
    tasks = [(abs, -2, "a"), (abs, 3, "b"), (float, "4", "c")]
    for workers in (1, 2):
        told: list[str] = []
        with Background(workers) as pool:
            started = pool.start(tasks)
            assert pool.results(started, told.append) == [2, 3, 4.0]
        assert told == ["a", "b", "c"]


def test_held_tasks_start_behind_the_next():
    """Tasks started `later` go on the pool behind the next start's tasks, or when a result is
    asked: every result got, in each call's order."""
    for workers in (1, 2):
        with Background(workers) as pool:
            held = pool.start([(abs, -1, "")], later=True)
            assert held[0][0] is None  # not on the pool yet
            first = pool.start([(abs, -2, "")])
            assert pool.results(first, print) == [2] and pool.results(held, print) == [1]
            again = pool.start([(abs, -5, "")], later=True)
            assert pool.results(again, print) == [5]
