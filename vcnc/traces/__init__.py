"""Readers for axis traces exported by CNC controls (issue #17); each produces a `vcnc.capture.Capture`."""

from vcnc.traces.tncscope import read_tncscope

__all__ = ["read_tncscope"]
