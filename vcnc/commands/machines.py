"""``vcnc machines``: list the built-in machines, or print one's definition."""

from __future__ import annotations

import argparse
import sys

HELP = "list built-in machines (--show NAME|FILE prints a definition)"

#: The machine context of part programs, printed (commented out, with its defaults) by ``--show``
#: after a definition that has no ``[program]`` table of its own.
PROGRAM_TABLE_DOC = """
# Machine context of part programs (optional; these defaults change nothing). Uncomment to use.
# [program]
# dialect = "linuxcnc"           # linuxcnc | fanuc | haas | grbl | fadal: G04 P in s (linuxcnc, grbl) or ms
# default_units = "mm"           # units of a program that states neither G20 nor G21 (mm | inch)
# continuous_path = true         # path mode of a program that states neither G61 nor G64
# tolerance = 0.01               # mm, path tolerance of that continuous-path mode
# home = [0.0, 0.0, 0.0]         # mm, machine coordinates: where programs start; G28's position
# reference2 = [0.0, 0.0, 0.0]   # mm, machine coordinates: G30's position
# linear_units = "mm"            # mm | inch: unit of the stored offsets a program reads (#5221.., #5401..)
# decimal_point_input = "calculator"  # fanuc: X10 without a decimal point is 10 mm (DPI=1); "increment": 0.010 mm
# tool_offset_memory = "C"       # fanuc tool compensation memory: C geometry and wear apart for H and D (G10 L10-L13,
#                                # #11001.. #10001.. #13001.. #12001..); B one geometry and wear per offset number;
#                                # A one value per offset number
#   length_offset_motion = true  # optional, the dialect's rule by default (true: fanuc, haas, fadal; false:
#                                # linuxcnc, grbl): a tool length change (G43/G44 H, G49) is an axis movement, added
#                                # to the next incremental Z and moving Z in a G00/G01 G43 block without Z (Fanuc
#                                # TOS = 0, No. 5006#6); false: a shift of the coordinates, the tool moving at the
#                                # next Z word only (TOS = 1, LinuxCNC)
# tool_table = "tools.tbl"       # a LinuxCNC tool table: T1 P1 D6.0 Z+12.5 ;comment (D diameter, Z length,
#                                # X Y offsets), or a Heidenhain TOOL.T (BEGIN TOOL .T MM; T NAME L R DL DR columns)
# subroutine_path = []           # folders searched for o<name> subroutine files, e.g. ["subs"] (SUBROUTINE_PATH)
# user_m_path = []               # folders holding the M100-M199 user programs, e.g. ["mfiles"] (USER_M_PATH)
#   initial_feed = 500.0         # optional, unset by default (such a move is then an error): mm/min, the feed of
#                                # a feed move before any F word (the control's power-on feed, Fanuc No. 1411)
#   wrap_direction = "sign"      # optional, for the rotary axes marked [axes.a] wrap = true (modulo axes that
#                                # wrap at 360 deg; unset: none wraps, 350 then A10 turns back 340 deg): the way an
#                                # absolute move turns: sign (the word's sign, |word| < 360: LinuxCNC WRAPPED_ROTARY,
#                                # Fanuc RAB=1) | shortest (Fanuc RAB=0, TNC M126) | difference (the TNC without
#                                # M126: from the angle shown below 360); unset: the control's own (linuxcnc sign,
#                                # heidenhain difference and M126 shortest, the others shortest). G91 is never wrapped
#   peck_tapping = "high-speed"  # optional, fanuc, set with peck_tapping_d (unset: refused, the manuals giving no
#   peck_tapping_d = 1.0         # default): M29 S.. / G84 (G74) .. Q.. is Fanuc's peck rigid tapping, Q each cut:
#                                # high-speed (PCP = 0, No. 5200#5: back by d [mm], No. 5213, after each cut) or
#                                # standard (PCP = 1: back to R after each cut, in again to d above the depth cut)
#
# [program.work_offsets]         # mm, machine coordinates of each work zero (G54 ... G59.3)
# G54 = [0.0, 0.0, 0.0]
# "G54.1 P1" = [0.0, 0.0, 0.0]   # Fanuc additional offsets G54.1 P1 .. P300 (G10 L20 P1 sets it); the Haas
#                                # G154 P1 .. P99 (G110 .. G129 = G154 P1 .. P20) are the same entries
# E7 = [0.0, 0.0, 0.0]           # Fadal fixture offsets E7 .. E48 (E1 .. E6 are G54 .. G59; E0: none)
#
# [program.tools.1]              # per tool number: G43 H1 applies the length, G41/G42 D1 the radius
# length = 0.0                   # mm
# radius = 0.0                   # mm
# offset_x = 0.0                 # mm, tool offsets along X and Y (G43 applies them with the length)
# offset_y = 0.0                 # mm
# name = ""                      # the tool's name: Heidenhain TOOL CALL "NAME" calls it
#
# [program.touch_probe]          # Heidenhain touch probe table row (TCH PROBE 4xx cycles on the nominal workpiece)
# set_up = 2.0                   # mm, SET_UP: safety clearance added to the cycle's Q320
# feed = 100.0                   # mm/min, F: probing feed
# fmax = 2000.0                  # mm/min, FMAX: pre-positioning and moves between the touch points
# dist = 20.0                    # mm, DIST: longest probing path
#   tip_radius = 3.0             # optional mm; unset: the radius of the probe's tool (TOOL CALL)
#
# Tilted working plane (Heidenhain PLANE / cycle 19, 3+2 machining) on a machine with rotary axes, e.g. [axes.b]
# and [axes.c]: the rotary axes that tilt the part (a head that tilts is an error for a tilted plane):
#   [program.kinematics]
#   kind = "table"               # table (trunnion: the part tilts) | head
#   [[program.kinematics.axes]]  # the outer (tilting) axis first: it carries the second, which carries the part
#                                # (a 4-axis machine: this table alone)
#   name = "b"                   # a | b | c, an axis of this machine
#   direction = "Y"              # X | Y | Z | -X | -Y | -Z: the machine axis it turns about (default a X, b Y, c Z)
#   pivot = [0.0, 0.0, -50.0]    # mm, a point of its axis of rotation (machine coordinates, rotary axes at 0)
#   limits = [-5.0, 110.0]       # deg
#   [[program.kinematics.axes]]
#   name = "c"
#   pivot = [0.0, 0.0, 0.0]
"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--show", metavar="NAME|FILE", help="print the TOML definition of a machine")


def run(args: argparse.Namespace) -> int:
    from vcnc.engine.machine import builtin_machine_text, builtin_machines, is_builtin_name, load_machine

    if args.show:
        name = args.show
        if is_builtin_name(name):
            text = builtin_machine_text(name)
        else:
            machine = load_machine(name)  # checks the file (MachineError -> exit 2)
            with open(machine.source or name) as fh:
                text = fh.read()
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        if "[program" not in text:
            sys.stdout.write(PROGRAM_TABLE_DOC)
        return 0
    names = builtin_machines()
    width = max(len(n) for n in names)
    for n in names:
        m = load_machine(n)
        print(f"{n:<{width}}  {', '.join(m.axes)}  Ts={m.sample_time * 1e3:g} ms  {m.description}")
    print("\nNAME+z (NAME+yz): the machine with a Z (Y and Z) axis added as a copy of its X axis, an assumption for "
          "programs that move it (e.g. fadal-pid+z; --show prints it)")
    return 0
