"""Fixtures: the paper's body and its models (helpers.py holds the shared functions)."""

import pytest

from formopt.mechanics.body import paper_body
from formopt.mechanics.model import build_model


@pytest.fixture(scope="session")
def body():
    return paper_body()


@pytest.fixture(scope="session")
def leg(body):
    return build_model(body, "leg")


@pytest.fixture(scope="session")
def shank_foot(body):
    return build_model(body, "shank-foot")
