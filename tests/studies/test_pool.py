"""studies.pool: the local process pool's ordered map (compare's band and strikes)."""

from formopt.studies.pool import independent


def test_independent_tasks_on_a_pool_keep_their_order():
    """Tasks on two processes (compare's band and strikes): results in the tasks' order, each told."""
    tasks = [(abs, -2, "a"), (abs, 3, "b"), (float, "4", "c")]
    for workers in (1, 2):
        told: list[str] = []
        assert independent(tasks, workers, told.append) == [2, 3, 4.0]
        assert sorted(told) == ["a", "b", "c"]
