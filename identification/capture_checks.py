"""Checks a capture axis must pass before identification or diagnosis.

Shared by :mod:`identification.identify` (the fit) and :mod:`identification.diagnosis` (the
augmentation), so that neither imports the other.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.ndimage import median_filter

from identification.bounds import WIDE_P_MIN_HZ
from identification.dead_time import LAG_STEP_S, follow_lag
from identification.poles import poles_from_denominator
from identification.regressor import RegressorOptions
from vcnc.core.axes import axis_unit
from vcnc.core.capture import UNIT_GIVEN, Capture, check_sampling
from vcnc.core.errors import CaptureError, IdentificationError

__all__ = ["check_capture", "travelled_direction", "check_channels", "MIN_SAMPLES", "MAX_SPAN_RATIO",
           "MIN_FOLLOW_CORRELATION", "MAX_SPEED_RATIO", "check_scale", "MAX_SCALE_ERROR",
           "check_jumps", "JUMP_FACTOR", "REFERENCE_JUMP_FACTOR", "JUMP_SHARE", "JUMP_WINDOW",
           "check_swapped", "polynomial_share", "channel_name", "HELD_TARGET_SHARE", "INTERPOLATED_SHARE",
           "RESPONSE_SHARE", "through_changes"]

#: Fewest samples accepted (the thesis' test has 22,000 at 1 ms; Sec. 4.3.3 4,096 at 0.6 ms). Slow loggers (4-8 ms
#: for a few seconds) give 150-450 samples, and 250 fit as well as 500 (measured 2026-11-25 with the first N samples
#: of decimated built-in captures against the 1 ms fit): on the 7 built-in machines at 4 and 8 ms (2 seeds each),
#: the first 250 samples' poles are
#: within 15 % of the 1 ms fit's and their RMS within 3x the noise floor + 1 um wherever the first 500's are (at
#: most 6 % off; held-out RMS on the rest of the record 1.00-1.10x the whole record's fit's, 500: 1.01-1.05x), and
#: where 500 fail so do 250 (ballscrew-zpetc's pole pair +49-54 %, chevalier-pdf's, fadal-pid's RMS at 8 ms). EMPS
#: (DATA_EMPS.mat at 4 and 8 ms, windows about a reversal: its first 500 move one way) keeps its pair within 5 % at
#: 250 as at 500. At 200 fadal-ppi's pair is 12 % off, at 150 16 % (8 ms).
MIN_SAMPLES = 250
#: Largest ratio of the measured to the commanded span (either way) of a position loop's record [-].
#: A loop follows its reference, so the spans agree within the tracking error and the overshoot (a
#: loop at 5 Hz, damping 0.33, on short moves: 1.6; a sluggish one on a short record: 0.2); a ratio
#: near one of :data:`_UNIT_RATIOS` (10 %) or beyond this is a channel in another unit.
MAX_SPAN_RATIO = 50.0
#: Least correlation of the measured with the commanded velocity, at the best lag, of a channel taken
#: for the axis' measured position [-] (:func:`identification.dead_time.follow_lag`): a position loop's
#: follows at 0.95 or more (chevalier-pdf's sluggish loop 0.948, EMPS 0.9999); mapped as the measured
#: position on fadal-pid, its velocity follows at 0.60, the y axis' position at 0.34, the control
#: signal at 0.10, the following error at 0.13, the position negated at 0.46.
MIN_FOLLOW_CORRELATION = 0.75
#: Below :data:`MIN_FOLLOW_CORRELATION` a channel is refused only when something else follows in its
#: place (:func:`_not_following`) or when it correlates less than this [-]: random loops of
#: ``tests/identification/test_properties.py`` (damping down to 0.1, 1 s records, 1 um noise on 5 mm
#: moves) follow at 0.74.
UNRELATED_CORRELATION = 0.5
#: Least correlation of what follows in the channel's place for the message to name it [-]: 0.999 for
#: fadal-pid's following error, velocity, negated position and y axis in x's place; a random loop of
#: ``test_properties.py`` with a zero in the right half-plane follows at 0.65, its commanded position
#: less it at 0.905.
EXPLAINED_CORRELATION = 0.98
#: A channel is taken for the following error only when it spans less than this share of the commanded
#: position [-] (fadal-pid's: 0.0076); a loop that barely moves (a random one of ``test_properties.py``)
#: leaves the commanded position less it following too.
FOLLOWING_ERROR_SPAN = 0.1
#: Largest ratio of the measured to the commanded velocity's RMS (on the record decimated to
#: :data:`identification.dead_time.LAG_STEP_S`) [-]: a loop's measured velocity is its reference's
#: filtered, 0.62-1.05 times it on the records of ``benchmarks/recorded_traces.py`` (chevalier-pdf
#: lowest, fadal-pid with overshoot highest), and up to its resonant peak 1 / (2 zeta) on a lightly
#: damped one (a random loop of ``tests/identification/test_properties.py``, zeta about 0.1: 3.02); a
#: rotary encoder in deg beside a linear reference in mm moves 360 / lead [mm] times faster (9 for a
#: 40 mm lead, 18 for 20 mm), which the span ratio lets pass.
MAX_SPEED_RATIO = 6.0
#: Largest deviation from 1 of the fitted loop's gain over the record's length (:func:`check_scale`) [-]:
#: 0.998-1.0016 on the machines of ``benchmarks/recorded_traces.py`` (plain, decimated to 6 ms, the
#: first 2 s) and on EMPS; their measured channel scaled by 1.2 gives 1.16-1.20.
MAX_SCALE_ERROR = 0.05

#: A measured position jumps where its velocity steps, against its neighbours', by more than this many
#: times the reference's largest acceleration step (or ten times its white noise, from the robust
#: deviation of its third difference, or three times its resolution) [-] (:func:`check_jumps`): at
#: most 1.5 on the records of ``benchmarks/recorded_traces.py`` and EMPS (a record logged every
#: 10 ms: 1.44); fadal-pid's measured channel with a 20 um jump in it: 9, one of 1 mm: 499.
JUMP_FACTOR = 5.0
#: A commanded position jumps where a step that stands out from its neighbours' (the velocity step
#: against their median over half the step) exceeds this many times the 99.9th percentile of the
#: steps that do not [-]: the largest step over that percentile is at most 1.07 on the records of
#: ``benchmarks/recorded_traces.py`` and 1.0 on EMPS; a rapid move among slow feeds is many steps, each
#: like its neighbours; a homing or a modulo rotary axis' wrap is one.
REFERENCE_JUMP_FACTOR = 5.0
#: A commanded position's jump is one (not a step command) when the measured position moves by at least this
#: share of it in one sample within :data:`JUMP_WINDOW` samples [-] (a loop answers a step over many samples).
JUMP_SHARE = 0.8
#: Samples either side of a commanded jump searched for the measured position's (a wrap of the measured
#: position comes after the commanded one's by the following error's lag) [-].
JUMP_WINDOW = 50
#: A jump within this of 360 [deg] is a rotary position shown modulo 360 that wrapped.
WRAP_TOLERANCE_DEG = 1.0

#: A channel moves like an interpolator's output when its jerk (third difference; fourth for an S-curve's
#: piecewise-constant jerk) is zero, to within 1e-3 of its largest, on at least this share of the samples
#: where both channels move (:func:`polynomial_share`) [-]: the commanded positions of
#: ``benchmarks/recorded_traces.py`` 0.60-0.99 when logged unrounded (0.60 at 10 ms), EMPS' 0.99; the
#: measured positions there at most 0.35 (a loop's response, encoder steps and noise), EMPS' 0.19.
INTERPOLATED_SHARE = 0.6
#: ... and the commanded channel is taken for a measured position when its share is at most this [-]
#: (a commanded position rounded to 1 um or 0.1 um digits: 0.25-0.40, so a trace rounded so is left alone).
RESPONSE_SHARE = 0.4
#: Relative size below which a jerk counts as zero [-].
_ZERO_JERK = 1e-3
#: A sample counts as moving when both channels move by more than this share of their largest step [-].
_MOVING = 0.01

#: The fit has dropped integral action when its p is at most this [Hz] (1.5 times the widened box's
#: bound, :data:`identification.bounds.WIDE_P_MIN_HZ`).
NO_INTEGRAL_P_HZ = 1.5 * WIDE_P_MIN_HZ

#: Unit ratios a span ratio is compared with, for the message.
_UNIT_RATIOS = {1000.0: "um beside mm", 25.4: "mm beside inch", 25400.0: "um beside inch", 10.0: "0.1 mm or 1/10 "
                "units", 1e4: "0.1 um increments beside mm"}
#: Relative distance from a unit ratio within which a span ratio is taken for it [-].
_UNIT_TOLERANCE = 0.1



def check_capture(capture: Capture, axis: str, *, options: RegressorOptions | None = None) -> tuple:
    """Validate one axis of a capture for identification; returns ``(reference, measured, T)``.

    Raises
    ------
    CaptureError
        Unknown axis, NaN/inf, time not increasing or not uniform.
    IdentificationError
        Fewer than :data:`MIN_SAMPLES` samples, no motion, too little motion either way
        (:func:`travelled_direction`; motion one way only is identified),
        measurement identical to the reference, positions that look like metres (too small a motion when
        ``meta[UNIT_GIVEN]`` states their unit), a measured
        channel that does not follow the commanded one (another axis', a velocity, the following
        error, a flipped sign) or in another unit (:func:`check_channels`).
    """
    src = capture.source
    i = capture.axis_index(axis)
    t = np.asarray(capture.t, float)
    n = t.size
    if n < MIN_SAMPLES:
        raise IdentificationError(
            f"only {n} samples; identification needs at least {MIN_SAMPLES} (the thesis' test has 22,000 at 1 ms)",
            file=src,
        )
    xr = np.asarray(capture.reference[:, i], float)
    x = np.asarray(capture.measured[:, i], float)
    for name, arr in (("t", t), (f"{axis}_ref", xr), (axis, x)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise CaptureError(
                f"column {name!r} is not finite at sample {int(bad[0])} (value {arr[bad[0]]!r})", file=src
            )
    check_sampling(t, src or "<capture>")
    T = capture.sample_time  # the nominal period (time stamps as decimals give 0.0010000000000000009)
    span = float(np.ptp(xr))
    u = axis_unit(axis)  # mm, or deg on a rotary axis
    if span == 0.0:
        moving = [a for j, a in enumerate(capture.axes) if j != i and np.ptp(capture.reference[:, j]) > 0.0]
        hint = f"; the commanded motion is on {', '.join(moving)} (identify one of them: --axis {moving[0]})" \
            if moving else ""
        what, stays = (("no motion", "reference and measurement stay") if float(np.ptp(x)) == 0.0
                       else ("no commanded motion", "the reference stays"))
        raise IdentificationError(f"{what} on axis {axis!r}: {stays} at {float(xr[0])!r} {u}{hint}", file=src)
    vmax = float(np.max(np.abs(np.diff(xr)))) / T
    if span < 1.0 and vmax < 2.0:
        if capture.meta.get(UNIT_GIVEN):
            raise IdentificationError(
                f"too small a motion to identify on axis {axis!r}: the reference spans {span:.4g} {u} at a peak speed "
                f"of {vmax:.4g} {u}/s in the unit stated ({capture.meta[UNIT_GIVEN]}); a loop is identified from "
                f"moves of 1 {u} or more, or faster than 2 {u}/s",
                file=src,
            )
        look = ("radians, not deg" if u == "deg" else
                "metres, not mm (or radians of a rotary joint, not deg)")
        how = ("deg (radians: --unit rad" if u == "deg" else
               "mm (a logger's metres: --unit m; radians: --unit rad with the axis named a, b or c")
        raise IdentificationError(
            f"positions on axis {axis!r} look like {look}: the reference spans {span:.4g} {u} at a peak speed of "
            f"{vmax:.4g} {u}/s; convert the capture to {how}; a test this small could not be identified anyway)",
            file=src,
        )
    if np.array_equal(xr, x):
        raise IdentificationError(
            f"the measured position of axis {axis!r} is identical to the reference at every sample: no tracking "
            f"error to identify from (was '{axis}_ref' copied into '{axis}'?)",
            file=src,
        )
    travelled_direction(x, T, axis, src, options=options)
    others = {a: np.asarray(capture.measured[:, j], float) for j, a in enumerate(capture.axes) if a != axis}
    check_channels(xr, x, T, axis, src, others=others, reference_name=channel_name(capture.meta, axis))
    check_swapped(xr, x, axis, src)
    check_jumps(xr, x, T, axis, src)
    return xr, x, T


def travelled_direction(measured: np.ndarray, sample_time: float, axis: str, src: str | None = None, *,
                        options: RegressorOptions | None = None) -> str:
    """Which way the measured position moves: ``"two-way"``, or ``"positive"`` / ``"negative"`` when it moves
    that way only (a :data:`identification.regressor.FRICTION_DIRECTIONS` value).

    A direction counts as travelled when at least ``max(20, 1 %)`` of the samples that move
    (speed above ``options.velocity_deadband``) move that way. A loop moving one way only is still
    identified (a weld seam, a feed axis' one-way test); only the Coulomb level of the direction it
    never travels is not, and :class:`~identification.regressor.RegressorOptions` ``friction`` then
    takes it as the mirror of the other's.

    Raises
    ------
    IdentificationError
        When neither direction is travelled so: too little motion to identify a loop from.
    """
    opt = options or RegressorOptions()
    v = np.diff(np.asarray(measured, float)) / sample_time
    db = opt.velocity_deadband
    n_pos, n_neg = int(np.sum(v > db)), int(np.sum(v < -db))
    need = max(20, int(0.01 * (n_pos + n_neg)))
    if n_pos < need and n_neg < need:
        raise IdentificationError(
            f"too little motion to identify on axis {axis!r}: {n_pos} samples with positive and {n_neg} with negative "
            f"measured velocity (at least {need} one way needed); record a test that moves the axis",
            file=src,
        )
    if n_pos >= need and n_neg >= need:
        return "two-way"
    return "positive" if n_pos >= need else "negative"


def _unit_hint(ratio: float) -> str:
    """A guess at the unit mix-up behind a span ratio (measured / commanded)."""
    big = ratio if ratio >= 1.0 else 1.0 / ratio
    which = "measured" if ratio >= 1.0 else "commanded"
    for r, text in _UNIT_RATIOS.items():
        if abs(big / r - 1.0) < _UNIT_TOLERANCE:
            return f" (about {r:g}: the {which} channel in a {r:g}x finer unit, {text}?)"
    return ""


def check_channels(reference: np.ndarray, measured: np.ndarray, sample_time: float, axis: str,
                   src: str | None = None, *, others: dict | None = None, reference_name: str | None = None) -> None:
    """IdentificationError unless the measured channel follows the commanded one in time, sign and scale.

    A position loop's measured position follows its reference (at a lag: its own response plus the
    recording's lead) and spans what the reference spans (within the tracking error). A channel
    that does not follow (another axis' position, a velocity, a current, the following error, the
    position negated) or one in another unit (mm and um, mm and inch, increments, deg of a rotary
    encoder) would otherwise be fitted silently: the flipped one to a model with negative gain, the
    rescaled one to nonsense poles, the others to a model of nothing (fadal-pid with its y axis'
    position as the measured x: 5221 um RMS, p on its 0.001 Hz bound).

    Parameters
    ----------
    reference, measured : ndarray
        Commanded and measured position [mm].
    sample_time : float
        [s].
    axis : str
        For the message.
    src : str, optional
        The capture's file, for the message.
    others : dict of str to ndarray, optional
        The measured positions of the capture's other axes: one that follows this axis' reference is
        named in the message (columns mapped to the wrong axes).
    reference_name : str, optional
        The trace's column (channel) read as the commanded position, for the message.

    Notes
    -----
    Following is judged on velocities (:func:`identification.dead_time.follow_lag`): their best
    correlation over lags up to a third of the record must reach :data:`MIN_FOLLOW_CORRELATION`. When
    it does not, the message names a commanded position that is a sequence of held targets
    (:func:`_held_targets`) or what does follow (:func:`_not_following`): the channel negated,
    the commanded position less it (a following error of either sign), its integral (a velocity), another
    axis' measured position. The span is the 0.1-99.9 % range, so a spike or a settling overshoot
    does not set it; a span ratio within reach of a loop's overshoot may still hide a channel in
    another unit, which moves faster than the loop could (:data:`MAX_SPEED_RATIO`).
    """
    xr = np.asarray(reference, float)
    x = np.asarray(measured, float)
    corr = follow_lag(xr, x, sample_time)[1]
    if corr < MIN_FOLLOW_CORRELATION:
        message = (_held_targets(xr, x, sample_time, axis, corr, reference_name) or _barely_moves(xr, x, axis, corr)
                   or _not_following(xr, x, sample_time, axis, corr, others or {}))
        if message or corr < UNRELATED_CORRELATION:
            raise IdentificationError(message or _unrelated(xr, sample_time, axis, corr), file=src)
    span_r = float(np.subtract(*np.percentile(xr, [99.9, 0.1])))
    span_x = float(np.subtract(*np.percentile(x, [99.9, 0.1])))
    q = max(1, int(round(LAG_STEP_S / sample_time)))
    dr, dx = np.diff(xr[::q]), np.diff(x[::q])
    speed = float(np.sqrt(np.dot(dx, dx) / np.dot(dr, dr))) if np.any(dr) else 1.0
    if span_r > 0 and span_x > 0:
        ratio = span_x / span_r
        if not 1.0 / MAX_SPAN_RATIO <= ratio <= MAX_SPAN_RATIO or _unit_hint(ratio) or speed > MAX_SPEED_RATIO:
            raise IdentificationError(
                f"axis {axis!r}: the measured position spans {span_x:.6g} and the commanded {span_r:.6g} (ratio "
                f"{ratio:.6g}; its velocity's RMS {speed:.4g} times the commanded one's)"
                f"{_unit_hint(ratio) or _rotary_hint(ratio)}; a position loop follows its reference, so "
                "the two channels must be in the same unit: give each channel's unit (a trace's unit row or header, "
                "--unit) or rescale one",
                file=src,
            )


def polynomial_share(reference: np.ndarray, measured: np.ndarray) -> tuple[float, float]:
    """``(commanded, measured)``: the share of the samples where both channels move on which each one's
    jerk is zero (:data:`INTERPOLATED_SHARE`): its third difference or, for an S-curve's piecewise-constant
    jerk, its fourth, whichever is more often zero (within 1e-3 of its largest)."""
    xr = np.asarray(reference, float)
    x = np.asarray(measured, float)
    dr, dx = np.abs(np.diff(xr)), np.abs(np.diff(x))
    if xr.size < 8 or not (np.any(dr) and np.any(dx)):
        return 0.0, 0.0
    moving = (dr > _MOVING * dr.max()) & (dx > _MOVING * dx.max())

    def share(y: np.ndarray) -> float:
        best = 0.0
        for order in (3, 4):
            d = np.abs(np.diff(y, order))[moving[:y.size - order]]
            if d.size and d.max() > 0:
                best = max(best, float(np.mean(d <= _ZERO_JERK * d.max())))
        return best

    return share(xr), share(x)


def check_swapped(reference: np.ndarray, measured: np.ndarray, axis: str, src: str | None = None) -> None:
    """IdentificationError when the commanded and measured channels look swapped (``--columns`` the wrong way).

    An interpolator's output moves piecewise-polynomially: a trapezoidal velocity profile's position is a
    quadratic between its breakpoints, an S-curve's a cubic, so its third (or fourth) difference is zero
    except at isolated samples; a measured position is a loop's response to it, with encoder steps and
    noise on top, whose jerk is seldom zero (:func:`polynomial_share`, :data:`INTERPOLATED_SHARE`,
    :data:`RESPONSE_SHARE`). A time shift cannot tell a swap from a reference recorded late, and fitting
    both ways round preferred the wrong one on fadal-ppi and chevalier-pdf (session 18); this signature
    does not depend on the timing. Swapped, fadal-pid's capture was fitted at 184 Hz, zeta 1.96 and
    3.97 um RMS (36.6 Hz / 0.425 / 1.14 Hz and 0.75 um the right way round). A commanded position logged
    rounded (to 1 um, or to 0.1 um at 3 ms) hides the signature, and such a swap is not named.
    """
    ref_share, meas_share = polynomial_share(reference, measured)
    if meas_share >= INTERPOLATED_SHARE and ref_share <= RESPONSE_SHARE:
        raise IdentificationError(
            f"axis {axis!r}: the commanded and measured channels look swapped: the measured one moves like an "
            f"interpolator's output (its jerk is zero, below a thousandth of its largest, on {meas_share:.0%} of the "
            f"samples in motion: piecewise-polynomial motion) and the commanded one like a measured position (on "
            f"{ref_share:.0%}: a loop's response, encoder steps, noise); map them the other way round (--columns "
            f"t=NAME,{axis}_ref=NAME,{axis}=NAME with the commanded position's column as {axis}_ref)", file=src)


def _rotary_hint(ratio: float) -> str:
    """For a span ratio no unit explains: what a rotary encoder logged in deg beside a linear reference gives."""
    if ratio <= 1.0:
        return ""
    return (f" (a rotary encoder in deg beside a linear reference in mm gives 360 / lead [mm/rev]: "
            f"{ratio:.4g} for a {360.0 / ratio:.3g} mm lead?)")


def _not_following(xr: np.ndarray, x: np.ndarray, T: float, axis: str, corr: float, others: dict) -> str:
    """The message for a measured channel that does not follow the commanded one: what it looks like instead,
    tried in turn (each must follow at :data:`EXPLAINED_CORRELATION`), and the remedy;
    "" when none does."""
    small = np.ptp(x) < FOLLOWING_ERROR_SPAN * np.ptp(xr)  # a following error is a small part of the motion
    tries = (
        (-x, "the measured channel's sign is flipped (an encoder, a motor mounted the other way or a trace "
             "channel counting the other way): negate it before identification"),
        *(((xr - x, "it looks like the following error (the commanded position less it follows the commanded at "
                    "{c:.3f}): map the actual position as the measured channel (--columns), or compute it as "
                    "commanded minus following error (mind your control's sign convention)"),) if small else ()),
        (np.cumsum(x) * T, "it looks like a velocity (integrated, it follows the commanded position at {c:.3f}): "
                           "map the position channel, not the velocity (--columns)"),
        *((v, f"the measured channel of axis {a!r} follows it (correlation {{c:.3f}}): the channels are mapped to "
              "the wrong axes (--columns, --axis-names) or --axis names the wrong one") for a, v in others.items()),
    )
    for signal, text in tries:
        c = follow_lag(xr, signal, T)[1]
        if c >= EXPLAINED_CORRELATION:
            return f"{_head(axis, corr)}: {text.format(c=c)}"
    return ""


#: A commanded position is a sequence of held targets (a positioning test's, a point-to-point move's) when the
#: measured one travels at least this share of its path while it stands still, and comes to rest at the value it
#: holds after at least :data:`HELD_TARGET_ARRIVALS` of its changes [-] (:func:`_held_targets`): an ecmc axis' ISO
#: 230-2 test logged by camonitor (X-PosCmd, 102 target updates in 2597 s) 1.00, arriving after all 101 changes;
#: the trajectories of a TNCscope trace, a LinuxCNC halscope log, a camber actuator log, UMich mill logs (0.1 s), a
#: UR joint log and a random-moves test 0.00-0.09, where a loop travels only its following error after the
#: reference stops; an electro-hydraulic actuator's setpoint updated every few of its 1 ms samples 0.56-0.66,
#: arriving after 0.1-0.3 % of its changes (it travels while the setpoint holds between updates, but never reaches
#: it before the next); a KUKA RSI weld log's Z_RSol, one 65.8 mm step the robot took over 40 samples of 12 ms,
#: 1.00. Measured on /tmp/realtrace11's set (session 35).
HELD_TARGET_SHARE = 0.8
#: ... and the share of the commanded position's changes after which the measured one reaches the new value (within
#: :data:`_ARRIVED` of the change) before the next [-].
HELD_TARGET_ARRIVALS = 0.5
#: The measured position moves at a sample when its step exceeds this share of its 99.9th percentile [-] (noise at
#: rest is no travel).
_TRAVEL = 0.05
#: The measured position has reached a held value when it comes within this share of the change to it [-].
_ARRIVED = 0.05


def channel_name(meta: dict, axis: str) -> str:
    """The trace's column read as the commanded position of ``axis`` (``meta["commanded"]``, ``"x:NAME,y:NAME"``
    as :mod:`vcnc.traces` writes it), else ``<axis>_ref``."""
    for item in str(meta.get("commanded") or "").split(","):
        a, _, name = item.partition(":")
        if a.strip() == axis and name:
            return name.strip()
    return f"{axis}_ref"


def _held_targets(xr: np.ndarray, x: np.ndarray, T: float, axis: str, corr: float, name: str | None) -> str:
    """The message for a commanded position that is a sequence of held targets, not a trajectory, "" otherwise: the
    measured position travels at least :data:`HELD_TARGET_SHARE` of its path while the commanded one stands still,
    and reaches the value held after most changes (:data:`HELD_TARGET_ARRIVALS`). A loop fed a trajectory travels
    only its following error after the trajectory stops, and a setpoint held between an interpolator's updates moves
    on before the axis reaches it; an axis sent to a target travels all the way after the target changed and stops
    there. Our reading: the target of a positioning test (ISO 230-2) or of
    a point-to-point move, logged in place of the setpoint the trajectory generator feeds the loop."""
    dr = np.abs(np.diff(xr))
    dx = np.abs(np.diff(x))
    top = float(np.percentile(dx, 99.9)) if dx.size else 0.0
    travel = dx * (dx > _TRAVEL * top)
    if top <= 0 or not np.any(dr) or float(np.sum(travel[dr == 0])) < HELD_TARGET_SHARE * float(np.sum(travel)):
        return ""
    edges = np.diff(np.concatenate(([0], (dr > 0).astype(int), [0])))
    first, last = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)  # the changes: samples first..last
    until = np.append(first[1:], xr.size - 1)  # held until the next change
    arrived = [float(np.min(np.abs(x[b:c + 1] - xr[b]))) <= _ARRIVED * abs(float(xr[b] - xr[a]))
               for a, b, c in zip(first, last, until, strict=True)]
    if not arrived or np.mean(arrived) < HELD_TARGET_ARRIVALS:
        return ""
    share = float(np.sum(travel[dr == 0]) / np.sum(travel))
    changes = "once" if len(arrived) == 1 else f"{len(arrived)} times"
    return (f"axis {axis!r}: the commanded position ({name or f'{axis}_ref'}) is a sequence of held targets, not a "
            f"trajectory: it changes {changes} in {x.size * T:.4g} s and stands still while the measured "
            f"position travels {share:.0%} of its path (velocity correlation {corr:.2f}; a positioning test's or "
            "point-to-point move's targets); identification needs the setpoint the trajectory generator "
            f"(interpolator) feeds the loop at its servo rate: record that channel and map it as {axis}_ref")


#: A commanded span within this many of the measured position's resolution (its smallest step) is too small a
#: motion to tell whether the measured channel follows [-]: the exact model of Table 3.4 moved over 7 um and recorded
#: with a 1 um encoder and 0.5 um noise correlates 0.20 (our reading of a "barely moving" axis; 10 mm: 0.99). The
#: noise is no such unit: a measured channel of 1 mm white noise beside an 18 mm move is another signal.
BARELY_MOVES_STEPS = 50


def _barely_moves(xr: np.ndarray, x: np.ndarray, axis: str, corr: float) -> str:
    """The message for an axis whose commanded motion spans fewer than :data:`BARELY_MOVES_STEPS` of the measured
    position's resolution, "" otherwise: its velocity is the encoder's steps and the noise, and the "does not follow"
    of :func:`_unrelated` (another axis', a velocity?) would send the user to the wrong remedy."""
    dx = np.abs(np.diff(x))
    step = float(np.min(dx[dx > 0])) if np.any(dx > 0) else 0.0
    span = float(np.ptp(xr))
    if step <= 0 or span >= BARELY_MOVES_STEPS * step:
        return ""
    u = axis_unit(axis, small=True)
    return (f"{_head(axis, corr)}: the axis barely moves: its commanded position spans {span * 1e3:.4g} {u}, "
            f"{span / step:.3g} times the measured position's resolution ({step * 1e3:.3g} {u}), which its velocity "
            f"is made of; record a test that moves it over at least {BARELY_MOVES_STEPS} steps "
            "(`vcnc toolpath identification` writes one)")


def _head(axis: str, corr: float) -> str:
    return (f"axis {axis!r}: the measured channel does not follow the commanded position (its velocity "
            f"correlates at most {corr:.2f} with the commanded one at any lag up to a third of the record; a "
            f"position loop's above {MIN_FOLLOW_CORRELATION:g})")


def _unrelated(xr: np.ndarray, T: float, axis: str, corr: float) -> str:
    return (f"{_head(axis, corr)}: it is not this axis' measured position (another axis', a velocity, a current or a "
            f"control signal?), or the two channels were recorded more than {xr.size * T / 3.0:.3g} s apart; check "
            "which column is mapped to it (--columns) and --axis")


def check_scale(parameters: dict, duration_s: float, axis: str, src: str | None = None) -> float:
    """The fitted loop's gain at the record's own frequency, 1 / ``duration_s``; IdentificationError when
    it differs from 1 by more than :data:`MAX_SCALE_ERROR`.

    A position loop takes its axis where it is sent: over the length of a record its measured position
    moves as far as the commanded one, and the fitted model of Eq. (3.3) then has a gain of 1 at
    that frequency (with integral action a3 > 0 exactly 1 at standstill). A measured channel scaled
    against the commanded one (an encoder's resolution, a gear ratio or a screw's lead set wrong, a
    unit the span check does not recognise) cannot be fitted with that gain: the fit drops the
    integral action (p on its lower bound) and takes the scale into b2 / a2 (fadal-pid with the
    measured channel x2: p 0.001 Hz for 1.14, 12 um RMS for 0.75, gain 2.000; fadal-ppi,
    ballscrew-ppc, chevalier-pdf x1.2 and x0.8: p 0.001 Hz and the gain the scale within 0.3 %).
    Only such a fit is judged (p at most :data:`NO_INTEGRAL_P_HZ`): a loop with integral action
    reaches gain 1 only below p, which a short record may not reach (``test_properties.py``'s random
    loops on 1 s records, p down to 0.05 Hz); a loop without it (EMPS) still has gain 1.
    Returns the gain (1.0 when not judged).

    Parameters
    ----------
    parameters : dict
        a1..d1 of Eq. (3.3).
    duration_s : float
        The record's length [s].
    """
    p = parameters
    slow = poles_from_denominator(p["a1"], p["a2"], p["a3"])
    if slow is None or slow["p_hz"] > NO_INTEGRAL_P_HZ:
        return 1.0
    s = 2j * math.pi / max(duration_s, 1e-9)
    gain = abs((p["b0"] * s ** 3 + p["b1"] * s ** 2 + p["b2"] * s + p["a3"])
               / (s ** 3 + p["a1"] * s ** 2 + p["a2"] * s + p["a3"]))
    if abs(gain - 1.0) > MAX_SCALE_ERROR:
        raise IdentificationError(
            f"axis {axis!r}: the measured position moves {gain:.4g} times as far as the commanded one (the fitted "
            f"loop's gain at {1.0 / duration_s:.3g} Hz, the record's length; a position loop's is 1): the channels "
            f"are scaled against each other (an encoder's resolution, a gear ratio or a screw's lead set wrong, or "
            f"another unit); rescale the measured channel by {1.0 / gain:.4g} or correct the trace's scaling",
            file=src,
        )
    return gain


def _velocity_steps(y: np.ndarray) -> np.ndarray:
    """Per sample step: how far the step ``y[k+1] - y[k]`` departs from the median of its 5 neighbours [mm]
    (signed)."""
    dy = np.diff(y)
    return dy - median_filter(dy, size=5, mode="nearest")


def check_jumps(reference: np.ndarray, measured: np.ndarray, sample_time: float, axis: str,
                src: str | None = None) -> None:
    """IdentificationError when either position jumps within the record.

    A homing, an encoder's reference mark, a datum or offset change, or a glitch of the trace moves a
    channel by a step in one sample, which no loop model explains: fitted, a 1 mm jump of fadal-pid's
    measured position gave omega_n 0.2 Hz and 267 um RMS (0.75 before), a 0.3 mm change of its datum
    offset 70 Hz / p 0.03 Hz and 72 um, a 5 mm jump of both channels 12 Hz for 37 and 22 um. A
    physical axis cannot do so: its velocity changes by at most its acceleration times the sample
    time per sample, about what its reference's does (:data:`JUMP_FACTOR`); an interpolator's
    reference moves by steps its neighbours share (:data:`REFERENCE_JUMP_FACTOR`). A step of the commanded
    position that the measured one does not make with it (:func:`_jumps_near`; nor a modulo rotary axis'
    360 deg wrap) is a step command, a drive's step-response test as commissioning tools record it: refused
    as such, since the fit is made for interpolated motion (the exact model ``FADAL_PID_X``, Table 3.4,
    answering steps of 0.05-0.2 mm, was fitted at 37.7 Hz / 0.54 / p 6.9 Hz for 33.0 Hz / 0.45 / 1.17 Hz).
    """
    x = np.asarray(measured, float)
    if x.size < 8:
        return
    xr = through_changes(reference)  # a reference held in steps jumps at every change
    jr = _velocity_steps(xr)
    dr = np.abs(np.diff(xr))
    alone = np.abs(jr) > 0.5 * dr  # a step unlike its neighbours'
    smooth = dr[~alone]
    top = float(np.percentile(smooth, 99.9)) if smooth.size else 0.0
    k = int(np.argmax(np.where(alone, dr, 0.0)))
    if alone[k] and dr[k] > REFERENCE_JUMP_FACTOR * top:
        if _is_wrap(float(jr[k])) or _jumps_near(x, k, float(xr[k + 1] - xr[k])):
            raise IdentificationError(_jump_message(axis, "commanded", float(jr[k]), k, sample_time), file=src)
        raise IdentificationError(
            f"axis {axis!r}: the commanded position steps by {float(xr[k + 1] - xr[k]):.4g} at sample {k + 1} "
            f"(t = {(k + 1) * sample_time:.6g} s from the record's start) and the measured one follows over many "
            "samples: a step command (a step-response test); vcnc identifies the loop from interpolated motion, a "
            "G-code test such as `vcnc toolpath identification` writes (its fit of an exact model's step responses "
            "misses the real pole 6x)", file=src)
    jx = _velocity_steps(x)
    sx = np.abs(jx)
    dx = np.abs(np.diff(x))
    resolution = float(np.min(dx[dx > 0])) if np.any(dx > 0) else 0.0
    noise = 1.4826 * float(np.median(np.abs(np.diff(x, 3)))) / math.sqrt(20.0)  # white noise's third difference
    scale = max(float(np.max(np.abs(np.diff(xr, 2)))), 10.0 * noise, 3.0 * resolution)
    d2 = np.abs(np.diff(x, 2))  # d2[i] about sample i + 1
    # the largest lasting step among quiet neighbours: a larger burst elsewhere, which passes, must not hide it, and a
    # step within a burst is the burst's
    lasting = _lasting(jx) & (sx > JUMP_FACTOR * scale) if scale > 0 else np.zeros(sx.size, bool)
    lasting[lasting] = [_quiet(d2, k - 1, k + 1, 0.25 * sx[k]) for k in np.flatnonzero(lasting)]
    k = int(np.argmax(np.where(lasting, sx, 0.0)))
    if lasting[k]:
        raise IdentificationError(_jump_message(axis, "measured", float(jx[k]), k, sample_time) + (
            f" (its velocity steps {sx[k] / scale:.3g} times as far in one sample as the commanded one's "
            "ever does)"), file=src)
    spike = _lone_spike(d2, jx, JUMP_FACTOR * scale) if scale > 0 else None
    if spike is not None:
        raise IdentificationError(
            f"axis {axis!r}: the measured position leaves its path by {abs(float(jx[spike])):.4g} mm at sample "
            f"{spike + 1} (t = {(spike + 1) * sample_time:.6g} s from the record's start) and is back at the next "
            "sample, its neighbours quiet: a glitch of the trace (a corrupted or misplaced sample), which no loop "
            "model explains; replace that sample by its neighbours' mean, or cut the record there", file=src)


def through_changes(reference: np.ndarray) -> np.ndarray:
    """The commanded position [mm] linear between the samples where it changes, when it is held in steps while it
    moves (IPO setpoints logged faster than the interpolator updates them: the median number of samples between
    changes is 2 or more), else as recorded.

    A value holds from its first sample; a rest (a value held over more than twice the median) also keeps its last
    sample, so the line does not move through it. Our reading: a 4 ms interpolation cycle logged at 1 ms moves the
    reference 0.4 mm every fourth sample at 100 mm/s, and the jump check took each step for a step command
    (:func:`check_jumps`); through its changes it is the interpolator's path.
    """
    xr = np.asarray(reference, float)
    first = np.flatnonzero(np.diff(xr) != 0.0) + 1
    if first.size < 10:
        return xr
    hold = float(np.median(np.diff(first)))
    if hold < 2:
        return xr
    starts = np.concatenate(([0], first))
    runs = np.diff(np.concatenate((starts, [xr.size])))  # samples each value holds
    rest_ends = (starts + runs - 1)[runs > 2 * hold]
    knots = np.unique(np.concatenate((starts, rest_ends, [xr.size - 1])))
    return np.interp(np.arange(xr.size), knots, xr[knots])


def _quiet(d2: np.ndarray, lo: int, hi: int, level: float) -> bool:
    """Whether the position's second difference ``d2`` (``d2[i]`` about sample ``i + 1``) stays under ``level``
    within ``LASTING_SAMPLES`` before ``lo`` and after ``hi`` (``d2[lo:hi]`` is the event's own)."""
    around = np.concatenate((d2[max(0, lo - LASTING_SAMPLES):max(0, lo)], d2[hi:hi + LASTING_SAMPLES]))
    return not np.any(around >= level)


def _lone_spike(d2: np.ndarray, steps: np.ndarray, threshold: float) -> int | None:
    """The step into a lone spike of the measured position (its sample is the next), if any: a step departing beyond
    ``threshold`` [mm] (``steps``: :func:`_velocity_steps`) answered by an opposite one at the next sample (they
    cancel to within a quarter), the position's second difference ``d2`` quiet around it (:func:`_quiet`, a quarter
    of the step). Our reading: a single corrupted sample; a burst of vibration or sampling jitter moves its
    neighbours too and passes."""
    for k in np.flatnonzero(np.abs(steps[:-1]) > threshold):
        a, b = float(steps[k]), float(steps[k + 1])
        if a * b < 0 and abs(a + b) <= 0.25 * abs(a) and _quiet(d2, k - 1, k + 2, 0.25 * abs(a)):
            return int(k)
    return None


#: Samples either side of a measured step over which :func:`_lasting` sums its velocity's departures [-].
LASTING_SAMPLES = 10


def _lasting(steps: np.ndarray) -> np.ndarray:
    """For each sample ``k``, True when the measured position's step there stays: the departures of its per-sample
    steps from their neighbours' median (:func:`_velocity_steps`) over ``LASTING_SAMPLES`` either side add up to at
    least half of the one at ``k``. Our reading: a jump (homing, reference mark, datum change, glitch) is one departure,
    and shifts the position for good; a burst of vibration or of sampling jitter departs and comes back, and adds
    up to little (a SINUMERIK 840D sl trace of an emergency-braking test: +-10 um per sample for 50 ms at
    105 mm/s, the following error 638 -> 624 -> 632 um, was refused as a 12 um jump)."""
    k = np.arange(steps.size)
    lo, hi = np.maximum(0, k - LASTING_SAMPLES), np.minimum(steps.size, k + LASTING_SAMPLES + 1)
    total = np.concatenate(([0.0], np.cumsum(steps)))
    return np.abs(total[hi] - total[lo]) >= 0.5 * np.abs(steps)


def _is_wrap(step: float) -> bool:
    """A step of 360 deg: a rotary position shown modulo 360 that wrapped."""
    return abs(abs(step) - 360.0) < WRAP_TOLERANCE_DEG


def _jumps_near(x: np.ndarray, k: int, step: float) -> bool:
    """Whether the measured position ``x`` also moves by most of ``step`` [mm] in one sample within
    :data:`JUMP_WINDOW` samples of sample ``k``: a homing or datum change moves both channels so; a loop
    answers a step command over many samples."""
    dx = np.diff(x)[max(k - JUMP_WINDOW, 0):k + JUMP_WINDOW + 1]
    return bool(np.any(dx * np.sign(step) >= JUMP_SHARE * abs(step)))


def _jump_message(axis: str, which: str, step: float, k: int, T: float) -> str:
    if _is_wrap(step):
        return (f"axis {axis!r}: the {which} position jumps by {step:.4g} deg at sample {k + 1} (t = {(k + 1) * T:.6g} "
                "s from the record's start): a rotary axis' position shown modulo 360 deg wrapped; unwrap it (add or "
                "subtract 360 deg from there on) before identification")
    return (f"axis {axis!r}: the {which} position jumps by {step:.4g} mm at sample {k + 1} (t = {(k + 1) * T:.6g} s "
            "from the record's start): a homing, an encoder's reference mark, a datum or offset change or a glitch "
            "of the trace within the record, which no loop model explains; identify the parts before and after it "
            "separately (cut the record there)")
