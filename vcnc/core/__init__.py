"""The leaf layer of vcnc: the data types and errors every other package shares.

It imports no other project code (checked by import-linter, see ``pyproject.toml``):

- :mod:`vcnc.core.errors`: the exception types;
- :mod:`vcnc.core.io`: atomic file output;
- :mod:`vcnc.core.axes`: axis names and their units;
- :mod:`vcnc.core.setpoints`: :class:`Setpoints`, the interpolator's output;
- :mod:`vcnc.core.capture`: :class:`Capture` and its CSV contract.
"""
