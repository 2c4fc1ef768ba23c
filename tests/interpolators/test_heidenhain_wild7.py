"""Heidenhain programs of a seventh wild set (hyperMILL 2025 posts for a DMU 85 monoBLOCK and a DMC 105V, a Polish
TNC 640 shop program, a shop's keyway macro, Fusion posts): what the reader refused or named wrongly, each as a
hand-written program checked against the independent reference where it runs."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()


def checked(body: str):
    """The program read, and its blocks matched against the reference."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO)


def test_a_block_the_control_marked_error_is_named():
    # a shop's keyway macro holds 'ERROR = L XQ102 + Q9;': the TNC keeps a block it could not read with that
    # mark and runs no program holding one (our reading); before, "unknown or unsupported block 'ERROR'"
    text = "0 BEGIN PGM T MM\n1 Q9 = 0.001\n2 L X+0 Y+0 Z+5 R0 FMAX\n3 ERROR = L XQ102 + Q9;\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match=r"t.h:4:3: a block the control marked 'ERROR =' when it read the "
                                         r"program in .*the control does not run a program holding one"):
        parse_heidenhain(text, source="t.h", context=ZERO)


def test_ql_and_qr_parameters_move_the_tool_as_q_parameters_do():
    # TNC 640 user's manual (34059x-02), 9.1: QL0-QL499 local, QR0-QR499 remanent, used as Q parameters are
    # (the reference read Q alone before: 'QR1 = 150' unmodelled in a shop's iTNC 530 program); its FN 16 F-PRINT
    # of the values to a file moves nothing (TNC 640 user's manual, "FN 16: F-PRINT")
    prog = checked("1 QR1 = 150\n2 QL2 = QR1 / 3\n3 FN 1: QL3 = +QL2 + +QR1\n4 L X+QL2 Y+QL3 Z+QR1 R0 FMAX\n"
                   "5 FN 16: F-PRINT TNC:\\mask.a / TNC:\\out.txt\n6 L IX-QL2 FQR1")
    assert np.allclose([b.target for b in prog.blocks], [[50, 200, 150], [0, 200, 150]])
