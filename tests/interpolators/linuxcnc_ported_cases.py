"""LinuxCNC interpreter tests newer than Debian's linuxcnc source package, written out as small case folders.

``make test`` runs LinuxCNC's ``tests/interp`` cases in place from the source package Debian 12 ships
(linuxcnc 2.9.0~pre1+git20230208, downloaded from Debian's archive). Six cases the tests use were added to LinuxCNC
after that snapshot (2026; github.com/LinuxCNC/linuxcnc, tests/interp/<case>, master of 2026-08-22). Each is written
out here as the files of its folder: the program(s) without comments and with shorter DEBUG/PRINT texts, the rs274
command line of its test.sh, and the rs274 output lines the tests read (the offsets and units that map the moves,
the moves, the messages), with the values of LinuxCNC's ``expected`` file for that case.
"""

from __future__ import annotations

_RESET = """\
 N..... USE_LENGTH_UNITS(CANON_UNITS_MM)
 N..... SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
 N..... SET_G92_OFFSET(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
 N..... SET_XY_ROTATION(0.0000)
"""

#: Position and offset parameters across G20/G21: the position converts, the stored work (G10 L2) and axis
#: (G92) offsets #5221.. / #5211.. stay in the units they were set in (unit-conversion).
_UNITS = [" inch 1.000000 2.000000 3.000000 4.000000 5.000000 6.000000",
          " mm 25.400000 50.800000 76.200000 4.000000 5.000000 6.000000",
          " inch 1.000000 2.000000 3.000000 4.000000 5.000000 6.000000",
          *[" g54 1.000000 2.000000 3.000000 4.000000 5.000000 6.000000"] * 3,
          *[" g92 -1.000000 -2.000000 -3.000000 -4.000000 -5.000000 -6.000000"] * 3]
_POS = "#5420 #5421 #5422 #5423 #5424 #5425"
_G54 = "#5221 #5222 #5223 #5224 #5225 #5226"
_G92 = "#5211 #5212 #5213 #5214 #5215 #5216"

#: #5021-#5023 report the G53 position whatever the work offset, rotation, G92 or tool length offset
#: (machine-coord-params).
_COORDS = ["0.000000 0.000000 0.000000", "1.000000 2.000000 3.000000"] * 5 + [
    "1.000000 2.000000 3.000000", "1.000000 1.000000", "3.000000 3.000000"]

_SH_ALL = "rs274 -g test.ngc | awk '{$1=\"\"; print}' | sed 's/-0\\.0000/0.0000/g'\n"

PORTED_CASES: dict[str, dict[str, str]] = {
    "unit-conversion": {
        "test.sh": _SH_ALL,
        "test.ngc": "\n".join([
            "g20", "g54", "g92.1", "g10 l2 p1 x0 y0 z0 a0 b0 c0", "g0 x1 y2 z3 a4 b5 c6",
            f"(debug, inch {_POS})", "g21", f"(debug, mm {_POS})", "g20", f"(debug, inch {_POS})",
            "g10 l2 p1 x1 y2 z3 a4 b5 c6", "g54", f"(debug, g54 {_G54})", "g21", f"(debug, g54 {_G54})", "g20",
            f"(debug, g54 {_G54})", "g92 x1 y2 z3 a4 b5 c6", f"(debug, g92 {_G92})", "g21", f"(debug, g92 {_G92})",
            "g20", f"(debug, g92 {_G92})", "g92.1", "m2", ""]),
        "expected": _RESET + " N..... USE_LENGTH_UNITS(CANON_UNITS_INCHES)\n"
        " N..... STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 4.0000, 5.0000, 6.0000)\n"
        + "".join(f' N..... MESSAGE("{m}")\n' for m in _UNITS) + " N..... PROGRAM_END()\n",
    },
    "machine-coord-params": {
        "test.sh": "rs274 -g test.ngc -t test.tbl | awk '/MESSAGE/ {$1=\"\"; print}' | sed 's/-0\\.0000/0.0000/g'\n",
        "test.tbl": "t1 p1 x0 y0 z0\n",
        "test.ngc": "\n".join([
            "o<coords> sub", "g53 g0 x0 y0 z0", "(debug,#5021 #5022 #5023)", "g53 g0 x1 y2 z3",
            "(debug,#5021 #5022 #5023)", "o<coords> endsub",
            "o<suite> sub", "g54", "g92.2", "g10 l2 p1 x0 y0 z0 r0", "o<coords> call", "g10 l2 p1 x3 y7 z0 r0",
            "o<coords> call", "g10 l2 p1 x0 y0 z0 r45", "o<coords> call", "g10 l2 p1 x3 y7 z0 r45", "o<coords> call",
            "g10 l2 p1 x0 y0 z0 r0", "g92 x3 y7", "o<coords> call", "g92.2", "o<suite> endsub",
            "g21", "o<suite> call", "g43.1 z5", "g53 g0 x1 y2 z3", "(debug,#5021 #5022 #5023)", "g49",
            "g53 g0 x1 y2 z3", "(debug,#5021 #<_abs_x>)", "(debug,#5023 #<_abs_z>)", "m2", ""]),
        "expected": "".join(f' N..... MESSAGE("{m}")\n' for m in _COORDS),
    },
    "sub-call-from-sub": {
        "test.sh": "rs274 -g -i test.ini test.ngc | awk '{$1=\"\"; print}'\n",
        "test.ini": "[RS274NGC]\nSUBROUTINE_PATH=subs\n",
        "test.ngc": "o<caller> call [1] [2] [3]\nM2\n",
        "subs/caller.ngc": "o<caller> sub\n(PRINT,X caller: #1 #2 #3)\no<helper> call [4] [5] [6]\n"
                           "o<caller> endsub\nM2\n",
        "subs/helper.ngc": "o<helper> sub\n(PRINT,X helper: #1 #2 #3)\no<helper> endsub\nM2\n",
        "expected": " caller: 1.000000 2.000000 3.000000\n helper: 4.000000 5.000000 6.000000\n",
    },
    "g64-r-planner": {  # G64 P.. R.. (the planner's peak scale): accepted, no motion
        "test.sh": "rs274 -g test.ngc | awk '{$1=\"\"; print}'\n",
        "test.ngc": "G64\nG64 P1 R0.5\nG64 P1 R1\nG64 P1 R2.5\nG64 P1 R0.05\nG64 P1 R0\nG64 P1\nM2\n",
        "expected": _RESET + " N..... SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 1.000000)\n"
        " N..... SET_PLANNER_MODE(type=1, peak_scale=0.500000)\n N..... PROGRAM_END()\n",
    },
    "nested-sub-error": {  # a sub defined inside a called named sub: rs274 refuses
        "test.sh": "! rs274 -g -i test.ini test.ngc\n",
        "test.ini": "[RS274NGC]\nSUBROUTINE_PATH=subs\n",
        "test.ngc": "o<nested> call [7] [8] [9]\nM2\n",
        "subs/nested.ngc": "o<nested> sub\no100 sub\n(DEBUG, inner: #1 #2 #3)\no100 endsub\no100 call [4] [5] [6]\n"
                           "o<nested> endsub\nM2\n",
    },
    "nested-sub-in-file-error": {  # a numbered sub after the named sub's endsub in its file: rs274 refuses the call
        "test.sh": "! rs274 -g -i test.ini test.ngc\n",
        "test.ini": "[RS274NGC]\nSUBROUTINE_PATH=subs\n",
        "test.ngc": "o<sequential> call [7] [8] [9]\nM2\n",
        "subs/sequential.ngc": "o<sequential> sub\n(DEBUG, main: #1 #2 #3)\no200 call [4] [5] [6]\n"
                               "o<sequential> endsub\no200 sub\n(DEBUG, helper: #1 #2 #3)\no200 endsub\nM2\n",
    },
}
