"""Exception types of vcnc (defined in :mod:`vcnc.core.errors`, re-exported here)."""

from vcnc.core.errors import *  # noqa: F403 - the public path of the exception types
from vcnc.core.errors import __all__ as __all__
