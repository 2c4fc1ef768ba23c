/* The vcnc axis model, sampled at the sample time (no FMI in this file).
 *
 * Two forms, chosen at export (VCNC_STRUCTURED in vcnc_config.h), each reproducing the Python
 * model operation by operation (same order of floating-point operations; built without fused
 * multiply-add, -ffp-contract=off):
 *
 * EXACT FORM (the reduced model, plus the disturbance/output effects of a diagnosis):
 * the simulation contract of identification/reduced_model.py, with w extended as in
 * identification/augmented.py (_run_exact, _w_terms):
 *
 *     (s^3 + a1 s^2 + a2 s + a3) x = (b0 s^3 + b1 s^2 + b2 s + a3) x_r - s w      (Eq. 3.3 * s)
 *
 * scaled observer-canonical realisation (time scale W = a3^(1/3)), x_r by first-order hold and
 * w by zero-order hold from the exponential of the 6x6 augmented matrix, causal state
 * xi = z - N x_r, run on deviations r_k = x_r,k - x_r,0 from the first reference sample:
 *     x_k  = (C xi_k + d r_k) + x_r,0
 *     v_k  = Cv xi_k + dv r_k + dvs (r_k - r_k-1)
 *     w_k  = ((d0 if v_k > 0, d1 if v_k < 0, else 0) + wext_k) + e(v_k, x_k)   held over [k, k+1)
 *     xi_{k+1} = Phi xi_k + Gamma[:,0] r_k + Gamma[:,1] w_k
 * starting at rest (xi_0 = 0). wext_k = w_ext,k (input) + the time_periodic load at t_k = k T;
 * e(v, x) = friction_stribeck + friction_viscous_asymmetric + position_periodic terms
 * (identification.augmented._w_terms). The measured position adds the drift rate * t_k.
 *
 * The discretisation is computed here (vcnc_linalg.c's matrix exponential) whenever the
 * parameters differ from those the FMU was exported with; for the exported parameters the
 * matrices computed by scipy at export are used, so the FMU reproduces the Python model bit for
 * bit.
 *
 * SPLIT FORM (an in-loop element: delay, saturation, backlash, resonance): the sampled
 * controller + plant loop of identification.augmented._run_split, in absolute coordinates, with
 * the same disturbance terms (evaluated at the driven mass) and drift, and the saturation's
 * anti-windup (conditional integration of the law's accumulator, identification.kernels.run_split).
 */
#ifndef VCNC_MODEL_H
#define VCNC_MODEL_H

#include <stddef.h>

#define VCNC_NX 3            /* states of the reduced model */
#define VCNC_MAX_DELAY 4096  /* longest control delay [samples] (split form) */
#define VCNC_MAX_REF_DELAY 4096 /* longest reference dead time [samples] (delay_s of the model) */
#define VCNC_MAX_HARMONICS 64 /* longest Fourier series of the periodic effects */

typedef struct {
    double a1, a2, a3;       /* denominator of Eq. 3.3: [1/s], [1/s^2], [1/s^3] */
    double b0, b1, b2;       /* numerator of Eq. 3.3: [1], [1/s], [1/s^2] */
    double d0, d1;           /* friction for positive / negative velocity [mm/s^2] */
    double sample_time;      /* [s] */
    /* disturbance effects (neutral at 0) */
    double stribeck[3];      /* v_s [mm/s] (<= 0: off), s+ [mm/s^2], s- [mm/s^2] */
    double asym;             /* k_a [1/s]: k_a |v| in w */
    double pp_period;        /* P_x [mm] (<= 0: off) */
    double pp_coef[2 * VCNC_MAX_HARMONICS]; /* (A_h, B_h) [mm/s^2], h = 1..pp_harmonics */
    int pp_harmonics;        /* structural */
    int tp_on;               /* structural: time_periodic present */
    double tp_period;        /* P_t [s] (> 0) */
    double tp_mean;          /* [mm/s^2] */
    double tp_coef[2 * VCNC_MAX_HARMONICS]; /* (C_h, D_h) [mm/s^2], h = 1..tp_harmonics */
    int tp_harmonics;        /* structural */
    double drift;            /* output drift rate [mm/s] */
    double ref_delay_s;      /* reference dead time [s] (>= 0): the loop runs on x_ref delayed by it */
    double ref_delay;        /* the same in samples (computed at initialisation) */
    double filter_s;         /* setpoint filter [s] (>= 0, 0: none): the loop runs on the moving average of the
                                delayed x_ref over it (identification.setpoint_filter) */
    double filter;           /* the same in samples (computed at initialisation) */
    /* split form (structural: structured) */
    int structured;
    double viscous_rate;     /* plant viscous rate c [1/s] */
    int delay;               /* control delay [samples] */
    double saturation;       /* u_max [mm/s^2] (inf: none) */
    int anti_windup;         /* structural: the accumulator stops at u_max (conditional integration) */
    double integral_lead;    /* structural: tau [s], the accumulator integrates e + tau de/dt */
    double backlash;         /* play width [mm] (<= 0: none) */
    double res[4];           /* f [Hz] (<= 0: rigid), zeta, table share r, measured at table (1/0) */
    int substeps;            /* plant steps per sample (computed at initialisation) */
    double tm[3 * 4 * 6];    /* exact two-mass steps (identification.augmented.two_mass_matrices; computed
                                at initialisation): [Ad | Bd] over a substep, over the sample, stuck table */
} vcnc_parameters;

/* The two-mass steps embedded at export, with the mode they were computed for. */
typedef struct {
    double f, zeta, r, viscous_rate, sample_time;
    int substeps;
    double tm[3 * 4 * 6];
} vcnc_two_mass;

/* The sampled model (identification.reduced_model.DiscreteModel). */
typedef struct {
    double phi[VCNC_NX * VCNC_NX];   /* row-major */
    double gamma[VCNC_NX * 2];       /* row-major; columns x_r, w */
    double c[VCNC_NX], d;
    double cv[VCNC_NX], dv, dvs;
    double xi0[VCNC_NX];             /* rest state for x_r,0 = 1 mm */
} vcnc_discrete;

typedef struct {
    vcnc_parameters par;
    vcnc_discrete dm;
    int exported;                    /* dm is the one embedded at export */
    long long k;                     /* samples since initialisation */
    /* exact-form state */
    double xi[VCNC_NX];
    double prev;                     /* r of the previous sample [mm] */
    /* split-form state */
    double xm, vm, xt, vt, xb;       /* driven (motor) mass, table, load side of the play [mm, mm/s] */
    double integ, yprev, rprev, vrprev;
    double held, eprev;              /* accumulator steps held back by the anti-windup; e of the last sample */
    double ubuf[VCNC_MAX_DELAY + 1]; /* delay line of u */
    /* inputs */
    double x_ref;            /* commanded position [mm] */
    double rbuf[VCNC_MAX_REF_DELAY + 2]; /* past x_ref, for the reference dead time */
    double rfirst;           /* x_ref of sample 0 [mm] */
    double lbuf[VCNC_MAX_REF_DELAY + 2]; /* past delayed x_ref, for the setpoint filter */
    double lfirst;           /* delayed x_ref of sample 0 [mm] */
    double r0;               /* x_ref at initialisation [mm]: the exact form runs on x_ref - r0 */
    double w_ext;            /* external disturbance [mm/s^2] */
} vcnc_model;

/* Continuous scaled realisation: A (3x3), B (3x2: columns x_r, w), C, D (position), Cv, Dv
 * (velocity, without its b0 dx_r/dt part); W the time scale [rad/s]. */
void vcnc_model_realise(const vcnc_parameters *p, double A[9], double B[6], double C[3], double D[2],
                        double Cv[3], double Dv[2], double *W);

/* Sample the model at p->sample_time. Returns 0, or -1 with a reason in msg. */
int vcnc_model_discretize(const vcnc_parameters *p, vcnc_discrete *dm, char *msg, size_t msg_size);

/* The parameters and discretisation embedded at export (vcnc_exported.c). */
extern const vcnc_parameters vcnc_exported_parameters;
extern const vcnc_discrete vcnc_exported_discrete;
extern const vcnc_two_mass vcnc_exported_two_mass;

/* Check the parameters, discretise, and put the model at rest at the current x_ref.
 * Returns 0, or -1 with a reason in msg. */
int vcnc_model_initialize(vcnc_model *m, char *msg, size_t msg_size);

/* Measured position [mm] and tracking error x_ref - position [mm] for the current state and
 * inputs (exact form: direct feedthrough, reflects x_ref as soon as it is set). */
void vcnc_model_outputs(const vcnc_model *m, double *position, double *tracking_error);

/* Advance one sample with the current inputs held. */
void vcnc_model_step(vcnc_model *m);

/* 0 while the state is finite (and, split form, bounded as in the Python model). */
int vcnc_model_diverged(const vcnc_model *m);

#endif
