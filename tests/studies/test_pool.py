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
