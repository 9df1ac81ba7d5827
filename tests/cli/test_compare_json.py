"""compare with several trials: each keeps its own folder (issue 25). That --json prints only
JSON and each trial's report is written whole is checked on the scene run of
test_compare_command.test_scene_file_gives_one_table_across_trials."""


def test_two_trials_with_one_file_name_keep_their_own_folders():
    """run.c3d of two runners: each trial writes into its own folder (issue 25)."""
    from formopt.cli.compare import trial_folders

    trials = [{"trial": "a/run.c3d"}, {"trial": "b/run.c3d"}, {"trial": "c/other.c3d"}]
    assert trial_folders(trials) == ["run-1", "run-2", "other"]


def test_trial_folders_are_unique_for_any_set_of_trial_paths():
    """x/a.c3d, y/a.c3d and x/a-1.c3d: the third's own stem is not a numbered one's (issue 37);
    names that differ only in case are one folder on a case-insensitive file system."""
    from formopt.cli.compare import trial_folders

    for paths in (["x/a.c3d", "y/a.c3d", "x/a-1.c3d"], ["a-1.c3d", "x/a.c3d", "y/a.c3d", "a-1-1.c3d"],
                  ["A.c3d", "x/a.c3d"], ["x/a.c3d", "y/a.c3d", "a-2.c3d", "z/a-2.c3d"]):
        names = trial_folders([{"trial": p} for p in paths])
        assert len({n.casefold() for n in names}) == len(paths), (paths, names)
