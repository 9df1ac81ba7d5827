"""The real trials, read once per session: RBDS subject 001 (two speeds, C3D and text, force
plate) and the Running Injury Clinic runner (clusters only, no units, no force plate)."""

import pytest
from trials import FORCES25, HEIGHT, RUN25, RUN35, STATIC

from formopt.io import mocap
from formopt.measure import measure


@pytest.fixture(scope="session")
def static():
    return mocap.read(STATIC)


@pytest.fixture(scope="session")
def run35():
    return mocap.read(RUN35)


@pytest.fixture(scope="session")
def run25():
    return mocap.read(RUN25, FORCES25)


@pytest.fixture(scope="session")
def measured(run35, run25, static):
    """RBDS001 at 3.5 and 2.5 m/s, by speed."""
    return {3.5: measure(run35, static, HEIGHT), 2.5: measure(run25, static, HEIGHT)}
