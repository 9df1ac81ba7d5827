"""compare with several trials: each keeps its own folder (issue 25). That --json prints only
JSON and each trial's report is written whole is checked on the scene run of
test_compare_command.test_scene_file_gives_one_table_across_trials."""


def test_two_trials_with_one_file_name_keep_their_own_folders():
    """run.c3d of two runners: each trial writes into its own folder (issue 25)."""
    from formopt.cli.compare import trial_folders

    trials = [{"trial": "a/run.c3d"}, {"trial": "b/run.c3d"}, {"trial": "c/other.c3d"}]
    assert trial_folders(trials) == ["run-1", "run-2", "other"]
