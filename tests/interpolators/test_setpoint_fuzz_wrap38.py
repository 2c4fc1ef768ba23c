"""``benchmarks/setpoint_fuzz.py`` on a machine whose rotary axes wrap at 360 deg (``--wrap RULE``, ``--machine
FILE``): the sources run on the wrapping axes, the setpoints judged on the motion the axes really make, and the
``wrap`` check of each absolute word's end and turn (:func:`benchmarks.setpoint_fuzz.wrap_failures`)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from benchmarks.setpoint_fuzz import main, on_machine, run_case, wrap_failures, wrapping
from interpolators import parse_program
from interpolators.context import DIALECTS, INTERPOLATION_CONTEXT, MachineContext
from vcnc.engine.machine import builtin_machine_text

#: A170, A350 (+180: half a turn goes the positive way), then A10 with X: +20 deg to 370 the shorter way or by the
#: word's sign, -340 to 10 by the difference to the angle shown (rotary_wrap's rules; TNC 640 user's manual M126,
#: LinuxCNC WRAPPED_ROTARY, Fanuc B-63534EN/02 20.2, 15i B-63783EN-1 1.6.3).
TEXT = "G21 G90\nG0 A170.\nG0 A350.\nG1 X1. A10. F100.\nM2\n"


@pytest.mark.parametrize(("rule", "end"), [("shortest", 370.0), ("sign", 370.0), ("difference", 10.0)])
def test_wrap_check_passes_the_rule_the_reader_ran_and_names_another(rule: str, end: float):
    ctx = on_machine(INTERPOLATION_CONTEXT, wrapping(rule))
    assert ctx.wrapped_axes == ("a", "b", "c") and ctx.wrap_direction == rule
    program = parse_program(TEXT, source="w.ngc", context=ctx)
    assert float(program.blocks[-1].extra_target[0]) == end
    assert wrap_failures(program, TEXT, ctx) == []
    other = "difference" if rule != "difference" else "shortest"
    assert wrap_failures(program, TEXT, dataclasses.replace(ctx, wrap_direction=other)) == [
        f"wrap: line 4 A10. ({other}) from 350 ends at {end:g} (turn {end - 350.0:g})"]
    # a program the check cannot read simply (G91 somewhere, a parameter) is left to the other checks
    assert wrap_failures(program, TEXT.replace("G21", "G21 G91 G90"), dataclasses.replace(ctx, wrap_direction=other)) \
        == []


def test_a_source_keeps_its_context_but_the_wrap():
    fanuc = MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a", "u"), tools={})
    got = on_machine(fanuc, wrapping("sign"))
    assert (got.wrapped_axes, got.wrap_direction, got.dialect.name, got.extra_axes) == (("a",), "sign", "fanuc",
                                                                                       ("a", "u"))
    # a context without rotary axes (the TNC sources') gets none to wrap, and no rule
    assert on_machine(MachineContext(), wrapping("sign")).wrap_direction is None


@pytest.mark.parametrize("rule", ["sign", "shortest", "difference"])
def test_rotary_cam_on_wrapping_axes_keeps_every_invariant(rule: str):
    # rotary_cam seed 46300 (session 38's wrap runs): A, B, C words beside X/Y/Z, both profiles
    cases = run_case("rotary_cam", 46300, machine=wrapping(rule))
    assert [(outcome, fails) for outcome, _, _, fails in cases] == [("ok", []), ("ok", [])]


def test_the_command_line_takes_a_machine_file(tmp_path: Path, capsys):
    base = builtin_machine_text("fadal-pid")
    axis_a = base[base.index("[axes.x]"):base.index("[axes.y]")].replace("[axes.x", "[axes.a")
    machine = tmp_path / "wrap.toml"
    machine.write_text(base + "\n" + axis_a.replace("[axes.a]\n", "[axes.a]\nwrap = true\n", 1)
                       + '\n[program]\ndialect = "linuxcnc"\nwrap_direction = "shortest"\n')
    assert main(["--count", "1", "--seed", "46301", "--sources", "rotary_cam", "--machine", str(machine)]) == 0
    assert capsys.readouterr().out.splitlines()[-1].split() == ["rotary_cam", "2"]
    with pytest.raises(SystemExit) as exc:
        main(["--count", "1", "--sources", "rotary_cam", "--machine", str(tmp_path / "none.toml")])
    assert exc.value.code == 2 and "none.toml" in capsys.readouterr().err
