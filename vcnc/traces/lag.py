"""The measured position formed from a following error: ``commanded - following error``.

Servo engineers tuning a drive often trace the commanded position and the following error (lag)
rather than the actual position. Every control whose convention was found documents the following
error as the commanded less the actual position, so the actual position is the commanded less it:

- Siemens SINUMERIK: "Following error" (``ContDev``) read as setpoint - actual, the reader's reading
  since issue #17 (:mod:`vcnc.traces.sinumerik`; no Siemens document of the sign was looked up here);
- LinuxCNC: ``joint.N.f-error`` (``axis.N.f-error`` up to 2.7) is ``joint->ferror = joint->pos_cmd -
  joint->pos_fb`` (``src/emc/motion/control.c``, ``process_inputs``; motion(9): "The actual following
  error"), :mod:`vcnc.traces.halscope`;
- Beckhoff TwinCAT NC: ``PosDiff`` "Position difference (lag distance)" (``NCTOPLC_AXIS_REF``) is the
  position lag value = "current set position - actual position" (Beckhoff infosys, TF50x0 NC PTP,
  "Monitoring", Position Lag Monitoring), :mod:`vcnc.traces.twincat`;
- Heidenhain TNC: servo lag (``LAG``) is "the difference between nominal and actual positions" (TNC
  426/TNC 425/TNC 415 B/TNC 407 user's manual, MOD functions, "Position Display Types"); TNCscope's
  ``s diff`` is read so (our reading: no TNCscope document of the channel's sign was found),
  :mod:`vcnc.traces.tncscope`.

A sign read wrong gives a "measured" position that leads the command by the lag (twice it from the
true position), which identification would fit as nonsense. So every following error used is also
checked on the data (:func:`check_lag_sign`): where the command moves fast (at least half its top
speed, its 99th percentile), the following error regressed on the commanded velocity gives the time
by which the measured position lags, ``tau = sum(e v) / sum(v^2)``; a measured position leading by
more than one sample (``tau < -sample_time``) is an error naming the channel. The records of vcnc's virtual
machines (6 random moves, x axis, :func:`check_lag_sign` on commanded - actual) lag by 18.1 ms
(fadal-ppi), 13.3 (chevalier-pdf), 7.9 (ballscrew-ppc) and 7.1 ms (emps); a real LinuxCNC 2.8 log by
7.2 ms (tracewild's ``halscope_skyfire_svm2.log``). A loop with velocity feedforward or zero-phase
tracking has a lag near zero: 0.16 ms (fadal-pid), 0.015 ms (ballscrew-zpetc), and fadal-smc's
leads by 0.012 ms; its error is mostly the acceleration's, whose sign the loop sets: no check on the
data can tell such a channel's sign, and a following error with a lead within a sample is accepted,
recorded as ``"leads ... ms at speed"`` in ``Capture.meta`` for the user to judge.
"""

from __future__ import annotations

import numpy as np

from vcnc.core.errors import CaptureError

__all__ = ["subtract_following_error", "check_lag_sign", "FAST_SHARE", "TOP_PERCENTILE", "MIN_FAST_SAMPLES",
           "MAX_LEAD_SAMPLES"]

#: Samples count as fast where the commanded speed is at least this share of its top speed [-].
FAST_SHARE = 0.5
#: The top speed is this percentile of the commanded speed [%]: a glitch of one sample in a command
#: rounded to its digits does not set it.
TOP_PERCENTILE = 99.0
#: Fewest fast samples the sign is judged on; with fewer it is taken as documented [-].
MIN_FAST_SAMPLES = 10
#: Largest lead of the measured position over the commanded one accepted, in samples [-]: the
#: channels of one trace may be sampled up to about a sample apart, a reversed lag leads by 1/Kv.
MAX_LEAD_SAMPLES = 1.0


def check_lag_sign(commanded: np.ndarray, following_error: np.ndarray, sample_time: float, *, channel: str,
                   src: str, line: int | None = None, expected: str = "commanded - actual") -> str:
    """CaptureError unless ``following_error`` lags the command (module docstring); returns what
    was found, ``"lags 12.3 ms at speed"`` (or why it was not judged), for ``Capture.meta``.

    Parameters
    ----------
    commanded, following_error : ndarray
        One axis' commanded position and following error [mm or deg], sample by sample.
    sample_time : float
        The sampling period [s].
    channel : str
        The following error's channel, for messages.
    expected : str
        The convention the channel is read with, and its source, for messages.
    """
    v = np.gradient(np.asarray(commanded, dtype=float), sample_time)
    e = np.asarray(following_error, dtype=float)
    top = float(np.percentile(np.abs(v), TOP_PERCENTILE)) if v.size else 0.0
    fast = np.abs(v) >= FAST_SHARE * top if top > 0 else np.zeros(v.shape, dtype=bool)
    if int(np.count_nonzero(fast)) < MIN_FAST_SAMPLES:
        return "sign not judged (the command hardly moves)"
    tau = float(np.sum(e[fast] * v[fast]) / np.sum(v[fast] ** 2))
    if tau < -MAX_LEAD_SAMPLES * sample_time:
        raise CaptureError(
            f"following error channel {channel!r}: the commanded position less it leads the command by "
            f"{-tau * 1e3:.3g} ms at speed (the following error has the sign opposite to the velocity on "
            f"{int(np.count_nonzero(fast))} samples at over {FAST_SHARE:.0%} of the top speed {top:.6g}/s); "
            f"expected a following error of {expected}, which lags: is the channel's sign reversed? Trace the "
            "actual position instead, or negate the channel", file=src, line=line)
    if tau < 0:
        return (f"leads {-tau * 1e3:.3g} ms at speed: within a sample, accepted; a reversed channel of a loop with "
                "feedforward looks so")
    return f"lags {tau * 1e3:.3g} ms at speed"


def subtract_following_error(commanded: np.ndarray, following_error: np.ndarray, sample_time: float, *,
                             channel: str, src: str, line: int | None = None,
                             expected: str = "commanded - actual") -> tuple[np.ndarray, str]:
    """``commanded - following_error`` (one axis), after :func:`check_lag_sign`; returns the
    measured position and what the check found."""
    found = check_lag_sign(commanded, following_error, sample_time, channel=channel, src=src, line=line,
                           expected=expected)
    return np.asarray(commanded, dtype=float) - np.asarray(following_error, dtype=float), found
