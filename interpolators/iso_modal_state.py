"""LinuxCNC's M70-M73: the modal state saved and restored by the program.

LinuxCNC M-code reference (``docs/src/gcode/m-code.adoc`` "M70 Save Modal State", "M71 Invalidate Stored
Modal State", "M72 Restore Modal State", "M73 Save and Autorestore Modal State"; ``interp_convert.cc``
``convert_m``, ``save_settings``, ``restore_settings``): ``M70`` saves the modal state at the current call
level (the main program, or one O-word subroutine invocation), ``M72`` restores it (the saved state stays
valid: it can be restored again), ``M71`` invalidates it, ``M73`` saves it and restores it when the
subroutine returns (``endsub`` or ``return``). The state: units (G20/G21), plane, cutter compensation,
distance mode, feed mode, coordinate system, tool length offset, retract mode, arc distance mode, path
mode, the F and S values, the spindle's state and the coolant (M7/M8: rs274 2.9.0~pre1 turns mist and flood
on again at M72); the motion mode is not restored.

In vcnc the saved state is the reader's own modal values (the tool length offset as the offsets in effect,
not the code that set them). Not modelled (errors naming them): an ``M72`` that would switch cutter
compensation on or off, or change its side. An ``M72`` with nothing saved at its level is an error in
LinuxCNC ("Cannot restore context from invalid stack frame - missing M70/M73?"); vcnc runs on, noted.
A restore takes effect where the block's M codes run, after its F, S, units, plane and distance words
(LinuxCNC restores before them: a G-code on the M72 line itself may come out differently).
"""

from __future__ import annotations

import copy

__all__ = ["SAVED_FIELDS", "ModalStates"]

#: The reader state's fields M70 saves (interpolators.iso ``State``).
SAVED_FIELDS = ("inch", "plane", "incremental", "arc_incremental", "inverse_time", "per_rev", "feed_reset", "wcs",
                "tool_length", "tool_xy", "length_code", "length_number", "retract_r", "exact_stop", "tolerance",
                "feed", "feed_rotary", "feed_zero", "feed_per_rev", "feed_per_rev_word", "spindle_speed",
                "spindle_turning", "spindle_ccw", "mist", "flood", "comp_side", "comp_radius")


class ModalStates:
    """The states saved per call level (0: the main program), each with its autorestore flag (M73)."""

    def __init__(self) -> None:
        self.saved: dict[int, tuple[dict, bool]] = {}
        self.level = 0

    def save(self, st, *, autorestore: bool) -> None:
        """M70 / M73 at the current level."""
        self.saved[self.level] = ({f: copy.copy(getattr(st, f)) for f in SAVED_FIELDS}, autorestore)

    def invalidate(self) -> None:
        """M71."""
        self.saved.pop(self.level, None)

    def restore(self, st) -> bool:
        """M72: the state saved at this level back in ``st``; False if none is saved.

        Raises
        ------
        ValueError
            The restore would change cutter compensation (its message names the change).
        """
        if self.level not in self.saved:
            return False
        state = self.saved[self.level][0]
        if (state["comp_side"], state["comp_radius"]) != (st.comp_side, st.comp_radius):
            raise ValueError(f"M72 would change cutter compensation (saved: {state['comp_side'] or 'off'}, now: "
                             f"{st.comp_side or 'off'})")
        for f, v in state.items():
            setattr(st, f, copy.copy(v))
        return True

    def enter(self, st, level: int, lowest: int) -> bool:
        """The call level of the next line is ``level``, the lowest level since the last line ``lowest`` (at most
        ``level``; below it after a subroutine's return then a call of the next: LinuxCNC
        tests/m70-m73/m73autorestore, ``o1000 call`` twice in a row): the levels left lose their states, an M73
        state of a level returned from is restored (True when one was)."""
        restored = False
        while self.level > lowest:
            state = self.saved.pop(self.level, None)
            if state is not None and state[1]:
                self.saved[self.level] = state
                restored = self.restore(st)
                self.saved.pop(self.level)
            self.level -= 1
        self.level = level
        return restored
