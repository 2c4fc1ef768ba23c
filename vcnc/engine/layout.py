"""Layout of the parameter vector the compiled kernel reads (one vector per axis).

Indices are module constants so the packer (:mod:`vcnc.engine.pack`) and the kernel
(:mod:`vcnc.engine.kernel`) agree; everything is in kernel units: positions mm, time s, forces
as control-signal equivalents V.
"""

from __future__ import annotations

# plant
PLANT_KIND = 0  # 0 rigid, 1 two-mass, 2 discrete transfer function
GAIN = 1  # K/J [mm/(V s^2)]
BETA_POS = 2  # viscous rate for v > 0 [1/s]
BETA_NEG = 3  # viscous rate for v < 0 [1/s]
FC_POS = 4  # Coulomb level + [V]
FC_NEG = 5  # Coulomb level - (magnitude) [V]
FS_POS = 6  # static level + [V]
FS_NEG = 7  # static level - (magnitude) [V]
V_STRIBECK = 8  # [mm/s], 0 off
SUBSTEPS = 9  # integration steps per sample
BACKLASH = 10  # total width [mm]
FEEDBACK_TABLE = 11  # 1: measure the table (linear scale), 0: the motor side
ENC_RES = 12  # [mm], 0 off
NOISE_STD = 13  # [mm]
DRIFT_RATE = 14  # [mm/s]
DRIFT_TAU = 15  # [s], 0 linear
DAC_LSB = 16  # [V], 0 off
DAC_RANGE = 17  # [V], 0 off
SAT = 18  # control limit [V], inf off
DELAY = 19  # samples
RES_OMEGA = 20  # [rad/s]
RES_ZETA = 21
RES_FRACTION = 22
PP_FORCE = 23  # position-periodic force amplitude [V]
PP_POS = 24  # lead error amplitude [mm]
PP_PERIOD = 25  # [mm], 0 off
PP_PHASE = 26  # [rad]
LOAD_CONST = 27  # [V]
LOAD_AMP = 28  # [V]
LOAD_PERIOD = 29  # [s]
LOAD_PHASE = 30  # [rad]
DPLANT_ORDER = 31  # discrete plant order n
DPLANT_SCALE = 32  # mm per output unit
SAMPLE_TIME = 33  # [s]
CTRL_KIND = 34
MEASURE_TABLE = 35  # 1: the capture records an independent linear scale on the table, 0: the feedback
LAW_LIMIT = 36  # the actuator limit the law's anti-windup knows [V], inf: no anti-windup (the bare law)
N_PLANT = 40

#: discrete plant coefficients b1..bn, a1..an follow the plant block (max order 8)
DPLANT_B = N_PLANT
DPLANT_A = N_PLANT + 8
N_TOTAL = N_PLANT + 16

# outputs (columns of the output matrix)
OUT_MEASURED = 0
OUT_TABLE = 1
OUT_VELOCITY = 2
OUT_CONTROL = 3
OUT_FRICTION = 4
OUT_POSITION = 5  # true position of the measured point [mm]: no sensor noise, quantisation, drift
OUT_LIMITED = 6  # 1.0 where the control was at its limit (actuator at its limit value, or anti-windup holding)
N_OUT = 7
