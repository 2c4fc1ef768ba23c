"""The ISO reader's tables of codes (:mod:`interpolators.iso`): the G codes it runs by modal group, those only
the Fanuc/Haas mill dialects or only LinuxCNC read, those it names in an error, and the M codes LinuxCNC knows.
Each table says its source where it is defined."""

from __future__ import annotations

from interpolators.context import WORK_OFFSETS
from interpolators.iso_haas import PATTERN_CODES
from interpolators.iso_offsets import EXTENDED_CODES
from interpolators.iso_position_offset import POSITION_OFFSET_CODES
from interpolators.iso_reference import FANUC_CODES, MILL_CODES, NAMED_CODES
from interpolators.iso_smoothing import SMOOTHING_CODES

__all__ = ["G_CODES", "LAST_ONE_VALID", "G_UNSUPPORTED", "MILL_G", "NORMAL_DIRECTION", "DIALECT_G", "LINUXCNC_G",
           "LINUXCNC_UNDEFINED", "PLANE_OF", "PLANE_CODES", "UNITS_HINT", "HURCO_BNC_HINT", "LINUXCNC_M",
           "LINUXCNC_ALLOCATED_G"]


#: G codes the reader runs, keyed by round(10 * code): (modal group, name).
G_CODES: dict[int, tuple[str, str]] = {
    **{k: ("motion", n) for k, n in ((0, "rapid"), (10, "linear feed"), (20, "clockwise arc"),
                                       (30, "counter-clockwise arc"), (800, "cycle cancel"),
                                       (50, "G5 cubic spline"), (51, "G5.1 quadratic spline"),
                                       (330, "G33 spindle-synchronised motion"), (331, "G33.1 rigid tapping"))},
    **{k * 10: ("motion", n) for k, n in ((73, "G73 peck drilling cycle"), (81, "G81 drilling cycle"),
                                          (82, "G82 drilling cycle with dwell"),
                                          (83, "G83 peck drilling cycle"), (84, "G84 tapping cycle"),
                                          (85, "G85 boring cycle"), (86, "G86 boring cycle"),
                                          (89, "G89 boring cycle with dwell"), (74, "G74 left-hand tapping cycle"),
                                          (76, "G76 fine boring cycle"), (87, "G87 back boring cycle"),
                                          (77, "G77 back boring cycle"))},
    40: ("dwell", "dwell"),
    100: ("nonmodal", "G10 set offsets"), 280: ("nonmodal", "G28 return home"),
    281: ("nonmodal", "G28.1 store home"), 300: ("nonmodal", "G30 second reference"),
    301: ("nonmodal", "G30.1 store reference"), 530: ("nonmodal", "G53 machine coordinates"),
    520: ("nonmodal", "G52 local offset"), 920: ("nonmodal", "G92 offset"), 921: ("nonmodal", "G92.1 offset reset"),
    922: ("nonmodal", "G92.2 offset suspend"), 923: ("nonmodal", "G92.3 offset restore"),
    170: ("plane", "XY"), 180: ("plane", "ZX"), 190: ("plane", "YZ"),
    200: ("units", "inch"), 210: ("units", "mm"),
    900: ("distance", "absolute"), 910: ("distance", "incremental"),
    901: ("arc distance", "absolute"), 911: ("arc distance", "incremental"),
    930: ("feed mode", "inverse time"), 940: ("feed mode", "per minute"), 950: ("feed mode", "per revolution"),
    400: ("cutter compensation", "off"), 410: ("cutter compensation", "left"),
    420: ("cutter compensation", "right"), 411: ("cutter compensation", "left"),
    421: ("cutter compensation", "right"),
    430: ("length compensation", "G43"), 431: ("length compensation", "G43.1"),
    440: ("length compensation", "G44"), 490: ("length compensation", "G49"),
    980: ("return mode", "G98"), 990: ("return mode", "G99"),
    610: ("path", "exact stop"), 611: ("path", "exact stop"), 640: ("path", "continuous"),
    960: ("spindle mode", "constant surface speed"), 970: ("spindle mode", "rpm"),
    690: ("rotation", "cancel"), 500: ("scaling", "cancel"), 150: ("polar", "cancel"),
    **{round(float(c[1:]) * 10): ("coordinate system", c) for c in WORK_OFFSETS},
}


#: Modal groups of which Fanuc takes the last G code when a block has two (the motion group, whose
#: cycle codes interact with G80, and the one-shot codes stay one per block).
LAST_ONE_VALID = frozenset({"plane", "units", "distance", "arc distance", "feed mode", "cutter compensation",
                             "length compensation", "return mode", "path", "spindle mode", "coordinate system"})


#: The G codes LinuxCNC defines (round(10 * code)): remap.adoc "Currently unallocated G-codes" (its tables of
#: allocated codes), with G33, G33.1, G38.2-G38.5, G43.2, G49, G52, G73 and G74 of g-code.adoc that those tables
#: leave out. Any other G code runs on LinuxCNC only where a configuration remaps it (REMAP= in its INI).
LINUXCNC_ALLOCATED_G = frozenset({
    0, 10, 20, 30, 40, 50, 51, 52, 53, 70, 80, 100, 170, 171, 180, 181, 190, 191, 200, 210, 280, 281, 300, 301, 330,
    331, 382, 383, 384, 385, 400, 410, 411, 420, 421, 430, 431, 432, 490, 520, 530, 540, 550, 560, 570, 580, 590,
    591, 592, 593, 600, 610, 611, 640, 700, 710, 711, 712, 720, 721, 722, 730, 740, 760, 800, 810, 820, 830, 840,
    850, 860, 870, 880, 890, 900, 901, 910, 911, 920, 921, 922, 923, 930, 940, 950, 960, 970, 980, 990})

#: G codes named in an error (round(10 * code) -> feature).
G_UNSUPPORTED: dict[int, str] = {
    **{k: "G38 probing" for k in (382, 383, 384, 385)},
    760: "G76 threading cycle (lathe)", 70: "G7 lathe diameter mode", 80: "G8 lathe radius mode",
    700: "G70 lathe finishing cycle", 710: "G71 lathe roughing cycle", 720: "G72 lathe facing cycle",
    711: "G71.1 lathe roughing cycle", 721: "G72.1 lathe facing cycle",
    750: "G75 lathe grooving cycle",
    52: "G5.2 NURBS block (LinuxCNC; --dialect linuxcnc)", 160: "G16 polar coordinates",
    510: "G51 scaling", 680: "G68 coordinate rotation",
    870: "G87 back boring cycle (Fanuc) / boring with manual retract (Haas)",
    880: "G88 boring cycle with manual retract", 770: "G77 back boring cycle (Haas mill)",
    120: "G12 circular pocket (Haas)", 130: "G13 circular pocket (Haas)",
    171: "G17.1 UV plane", 181: "G18.1 WU plane", 191: "G19.1 VW plane",
    432: "G43.2 additional tool length offset (LinuxCNC; --dialect linuxcnc)",
    682: "G68.2 tilted working plane (5-axis)", 683: "G68.3 tilted working plane (5-axis)",
    684: "G68.4 tilted working plane (5-axis)", 531: "G53.1 tool axis direction control (5-axis)",
    434: "G43.4 tool centre point control (5-axis; --dialect fanuc)",
    435: "G43.5 tool centre point control type 2 (5-axis; --dialect fanuc)",
    2340: "G234 tool centre point control (Haas 5-axis; --dialect haas)",
    24: "G02.4 three-dimensional circular interpolation (Fanuc option; --dialect fanuc)",
    34: "G03.4 three-dimensional circular interpolation (Fanuc option; --dialect fanuc)",
    2680: "G268 feature coordinate system (Haas 5-axis)",
    # Haas NGC mill operator's manual "G254 Dynamic Work Offset (DWO) (Group 23)": read under --dialect haas
    # (interpolators.iso_dwo). Fanuc "NURBS interpolation (G06.2)" (an option of the 30i series): read under
    # --dialect fanuc (interpolators.iso_fanuc_nurbs).
    2540: "G254 dynamic work offset (Haas DWO; --dialect haas)",
    2550: "G255 dynamic work offset cancel (Haas DWO; --dialect haas)",
    62: "G06.2 NURBS interpolation (Fanuc option; --dialect fanuc)",
    541: "G54.1 P additional work offsets (Fanuc; --dialect fanuc)",
    # FANUC Series 30i-B operator's manual (B-64484EN), "Workpiece setting error compensation (G54.4)": an option
    # whose error data the machine's probing stores; Fusion's fanuc.cps writes "G54.4 P<n>" after its probing
    # macros (G65 P98xx, refused by name) and "G54.4 P0" at the end
    544: "G54.4 workpiece setting error compensation (Fanuc option: its data comes from the machine's probing)",
    401: "G40.1 normal direction control cancel (Fanuc; --dialect fanuc)",
    1540: "G154 P additional work offsets (Haas; --dialect haas)",
    # named after the Haas mill operator's manual (G codes), Fanuc 0i-MF and TinyG/g2core:
    310: "G31 skip function (probing)", 282: "G28.2 homing cycle (TinyG/g2core)",
    283: "G28.3 set machine position (TinyG/g2core)",
    412: "G41.2 3-D cutter compensation (5-axis)", 422: "G42.2 3-D cutter compensation (5-axis)",
    # G45-G48 tool position offset: read under --dialect fanuc (interpolators.iso_position_offset); Haas's G47
    # engraves text (Haas mill operator's manual, "G47 Text Engraving")
    470: "G47 text engraving (Haas) / tool position offset double increase (Fanuc; --dialect fanuc)",
    450: "G45 tool position offset increase (Fanuc; --dialect fanuc)",
    460: "G46 tool position offset decrease (Fanuc; --dialect fanuc)",
    480: "G48 tool position offset double decrease (Fanuc; --dialect fanuc)", 1070: "G107 cylindrical mapping (Haas)",
    1410: "G141 3-D+ cutter compensation (Haas)", 1430: "G143 5-axis tool length compensation (Haas)",
    1500: "G150 general purpose pocket milling (Haas)",
    1740: "G174 non-vertical rigid tapping (Haas)", 1840: "G184 non-vertical rigid tapping (Haas)",
    **NAMED_CODES,  # G09, G22, G23, G27, G29, G60 outside the dialects that run them (interpolators.iso_reference)
}


#: Codes the ``fanuc`` and ``haas`` dialects read as a Fanuc/Haas mill does, before :data:`G_CODES` and
#: :data:`G_UNSUPPORTED` (where LinuxCNC's meaning, or an error, stays).
MILL_G: dict[int, tuple[str, str]] = {
    **{k: ("smoothing", n) for k, n in SMOOTHING_CODES.items()},
    680: ("rotation", "G68 coordinate rotation"),
    682: ("tilted plane", "G68.2 tilted working plane"), 531: ("tool axis", "G53.1 tool axis direction control"),
    740: ("motion", "G74 counter tapping cycle"), 760: ("motion", "G76 fine boring cycle"),
    510: ("scaling", "G51 scaling"), 500: ("scaling", "G50 scaling cancel"),
    511: ("mirror", "G51.1 programmable mirror image"), 501: ("mirror", "G50.1 mirror image cancel"),
    390: ("corner circular", "G39 corner circular interpolation"),
    **MILL_CODES,  # G09, G29, G60 (interpolators.iso_reference)
}


#: Fanuc normal direction control (Fanuc Series 0i-MB operator's manual B-63844EN/02, II-14.9 "Normal
#: direction control (G40.1, G41.1, G42.1 or G150, G151, G152)"; Mitsubishi M700V programming manual 13.14
#: "Normal line control; G40.1/G41.1/G42.1"): the rotary C axis is turned to stay normal to the XY path.
#: In LinuxCNC G41.1/G42.1 are dynamic cutter compensation (:data:`G_CODES`); G40.1 is no LinuxCNC code.
NORMAL_DIRECTION = {401: "G40.1 normal direction control cancel", 411: "G41.1 normal direction control left",
                     421: "G42.1 normal direction control right"}


#: Codes only one of the two mill dialects reads so: Fanuc's G87 back boring is Haas's G77 (Haas G87
#: bores with a manual retract).
DIALECT_G: dict[str, dict[int, tuple[str, str]]] = {
    "fanuc": {870: ("motion", "G87 back boring cycle"), 160: ("polar", "G16 polar coordinate command"),
              24: ("motion", "G02.4 three-dimensional circular interpolation"),  # interpolators.iso_arc3d
              62: ("motion", "G06.2 NURBS interpolation"),  # interpolators.iso_fanuc_nurbs
              34: ("motion", "G03.4 three-dimensional circular interpolation"),
              434: ("length compensation", "G43.4 tool centre point control"),  # interpolators.iso_tcp
              435: ("length compensation", "G43.5 tool centre point control type 2"),
              **{k: ("normal direction", n) for k, n in NORMAL_DIRECTION.items()}, **EXTENDED_CODES["fanuc"],
              **{k: ("position offset", n) for k, (n, _) in POSITION_OFFSET_CODES.items()},
              **FANUC_CODES,  # G22, G23, G27 (interpolators.iso_reference)
              700: ("units", "inch"), 710: ("units", "mm")},  # read leniently: see interpolators.iso ``_g70_g71_units``
    "haas": {770: ("motion", "G77 back boring cycle"), **{k: ("pattern", n) for k, n in PATTERN_CODES.items()},
             2340: ("length compensation", "G234 tool centre point control"),  # interpolators.iso_tcp
             2540: ("dwo", "G254 dynamic work offset"), 2550: ("dwo", "G255 dynamic work offset cancel"),  # iso_dwo
             120: ("pocket", "G12 circular pocket milling"), 130: ("pocket", "G13 circular pocket milling"),
             1010: ("mirror", "G101 mirror image"), 1000: ("mirror", "G100 mirror image cancel"),
             **EXTENDED_CODES["haas"]},
}


#: G87 and G88 under LinuxCNC: its g-code.adoc, "G87 Back Boring Cycle" and "G88 Boring Cycle, Spindle Stop, Manual
#: Out": "This code is currently unimplemented in LinuxCNC. It is accepted, but the behavior is undefined" (the
#: table of codes: "not yet implemented"). rs274 runs motions of its own (G87 wants I J K and moves through the
#: spindle orientations; G88 feeds to Z, dwells, stops the spindle and the program, and leaves the tool at the
#: bottom for the operator's manual retract); vcnc refuses them, naming the documentation.
_UNDEFINED = ("LinuxCNC's G-code reference: \"currently unimplemented in LinuxCNC. It is accepted, but the "
              "behavior is undefined\"")
LINUXCNC_UNDEFINED: dict[int, str] = {870: f" ({_UNDEFINED}; --dialect fanuc runs Fanuc's G87 back boring)",
                                      880: f" ({_UNDEFINED})"}


#: Codes only the ``linuxcnc`` dialect reads (the Fanuc/Haas dialects name them in an error). G8: LinuxCNC's
#: g-code.adoc "G8 Lathe Radius Mode": "the X axis moves ... will be the distance from the center ... G8 is
#: default at power up"; rs274 takes it on any machine. vcnc's X is always that distance (G7, diameter mode,
#: is refused), so G8 moves nothing: a mill program started from a lathe template ("G40 G8") runs as LinuxCNC
#: runs it.
LINUXCNC_G: dict[int, tuple[str, str]] = {432: ("length compensation", "G43.2 additional tool length offset"),
                                           52: ("motion", "G5.2 NURBS block"), 53: ("motion", "G5.3 NURBS end"),
                                           80: ("lathe mode", "G8 lathe radius mode")}


PLANE_OF = {"XY": 2, "ZX": 1, "YZ": 0}


#: The M codes below 100 LinuxCNC knows (interp_array.cc ems[], and M98/M99 subprograms); it refuses others.
LINUXCNC_M = frozenset({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 19, 30, 48, 49, 50, 51, 52, 53, 60, 61, 62, 63, 64, 65, 66,
                         67, 68, 70, 71, 72, 73, 98, 99})


#: The plane-selecting code of each plane (by its normal-axis index).
PLANE_CODES = {2: "G17", 1: "G18", 0: "G19"}


#: What a bare G70/G71 is on the controls that read it as units (interpolators.iso
#: ``_g70_g71_units``), for the dialects that refuse it (LinuxCNC 2.9 reads G70/G71 as lathe
#: cycles: rs274 "G7x.x requires a Q word").
#: A bare G75 (no word of the lathe cycle): Hurco's Basic NC (BNC) multi-quadrant arc mode, which Fusion's hurco.cps
#: writes at the program start when its ``isnc`` property is off ("multi-quadrant arc interpolation mode").
HURCO_BNC_HINT = (" (a bare G75 is the multi-quadrant arc mode of Hurco's Basic NC (BNC) programs: vcnc does not read "
                  "BNC; post for Hurco's ISNC mode, its ISO NC format, and read it with --dialect fanuc)")

UNITS_HINT = {key: f" (a unit code on Siemens, Fagor and Heidenhain ISO controls: {unit} input; write "
                    f"{code}, or read the program with --dialect fanuc)"
               for key, unit, code in ((700, "inch", "G20"), (710, "mm", "G21"))}
