"""Keyword arguments that were renamed: the old name still works, with a DeprecationWarning."""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["renamed_keywords"]

F = TypeVar("F", bound=Callable[..., Any])


def renamed_keywords(**renamed: str) -> Callable[[F], F]:
    """Let a function take its keyword arguments under old names as well.

    Parameters
    ----------
    **renamed : str
        ``old_name="new_name"`` for each renamed keyword argument.

    Returns
    -------
    callable
        A decorator: the decorated function passes an old name on as the new one, with a
        :class:`DeprecationWarning`; giving both names is a :class:`TypeError`. Its
        signature (:func:`inspect.signature`) is that of the function, new names only.

    Notes
    -----
    The wrapper is one more frame between the caller and the function: a warning the
    function issues for its caller needs ``stacklevel=3``.
    """

    def decorate(func: F) -> F:
        @functools.wraps(func)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            for old, new in renamed.items():
                if old not in kwargs:
                    continue
                if new in kwargs:
                    raise TypeError(
                        f"{func.__name__}() got both {old}= and {new}=; pass {new}= only"
                    )
                warnings.warn(
                    f"{func.__name__}({old}=...) is deprecated; pass {new}= instead",
                    DeprecationWarning,
                    stacklevel=2,
                )
                kwargs[new] = kwargs.pop(old)
            return func(*args, **kwargs)

        return wrapper  # type: ignore[return-value]

    return decorate
