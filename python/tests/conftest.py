import pathlib

import pytest

DATA = pathlib.Path(__file__).parent / "data"
REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def data():
    return DATA


@pytest.fixture
def repo():
    return REPO
