"""Exceptions raised by gvd. Every refusal of a scene names the site and field at fault."""

from typing import Optional

__all__ = [
    "Error",
    "SceneError",
    "UnsupportedError",
    "BudgetError",
    "OptionError",
    "DiagramError",
    "InternalError",
]


class Error(Exception):
    """Base class of gvd's exceptions. ``reason`` is the message without its prefix."""

    def __init__(self, message: str, *, reason: Optional[str] = None, **attrs):
        super().__init__(message)
        self.reason = reason if reason is not None else message
        for key, value in attrs.items():
            setattr(self, key, value)


class SceneError(Error, ValueError):
    """A scene was refused.

    ``site`` is the index of the site at fault (None for a scene-level field such as
    ``domain`` or ``epsilon``, or for text that does not parse); ``field`` the field at
    fault (``at``, ``rings``, ``metric.p``, ...; None when the error is between two
    sites); ``other`` the second site of a conflict (two sites that cross or overlap).
    """

    site: Optional[int]
    field: Optional[str]
    other: Optional[int]

    def __init__(self, message: str, *, site=None, field=None, other=None, reason=None):
        super().__init__(message, reason=reason, site=site, field=field, other=other)


class UnsupportedError(Error):
    """The scene is valid but the chosen engine cannot compute site ``site`` (of
    ``kind``) yet."""

    site: int
    kind: str

    def __init__(self, message: str, *, site=None, kind=None, reason=None):
        super().__init__(message, reason=reason, site=site, kind=kind)


class BudgetError(Error):
    """A computation reached a work limit: ``what`` ("boxes", "points" or "seconds") at
    ``limit`` (raise it with ``max_boxes=``, ``max_points=`` or ``timeout=``)."""

    what: str
    limit: int

    def __init__(self, message: str, *, what=None, limit=None, reason=None):
        super().__init__(message, reason=reason, what=what, limit=limit)


class OptionError(Error, ValueError):
    """An option (``engine``, ``grid``, ``slack``, ``distance`` ...) is out of range."""

    option: str

    def __init__(self, message: str, *, option=None, reason=None):
        super().__init__(message, reason=reason, option=option)


class DiagramError(Error, ValueError):
    """A diagram could not be read or does not fit its scene."""

    def __init__(self, message: str, *, reason=None):
        super().__init__(message, reason=reason)


class InternalError(Error, RuntimeError):
    """An engine could not complete (a bug, reported instead of a wrong diagram)."""

    def __init__(self, message: str, *, reason=None):
        super().__init__(message, reason=reason)
