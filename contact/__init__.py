"""contact: rough surfaces and their contact with a flat counter-face.

Turns a rough surface into a contact-pressure map and pressure samples for :mod:`glstat`.
"""

from .result import ContactResult
from .surface import Surface

__all__ = ["ContactResult", "Surface"]
