/* The vcnc reduced closed-loop axis model, sampled at the sample time (no FMI in this file).
 *
 * This is the simulation contract of identification/reduced_model.py, reproduced operation by
 * operation (same realisation, same discretisation, same order of floating-point sums):
 *
 *     (s^3 + a1 s^2 + a2 s + a3) x = (b0 s^3 + b1 s^2 + b2 s + a3) x_r - s w      (Eq. 3.3 * s)
 *     w = PV(v) d0 + NV(v) d1 + w_ext                                           [mm/s^2]
 *
 * scaled observer-canonical realisation (time scale W = a3^(1/3)), x_r by first-order hold and
 * w by zero-order hold from the exponential of the 6x6 augmented matrix, causal state
 * xi = z - N x_r:
 *     x_k  = C xi_k + d x_r,k
 *     v_k  = Cv xi_k + dv x_r,k + dvs (x_r,k - x_r,k-1)
 *     w_k  = (d0 if v_k > 0, d1 if v_k < 0, else 0) + w_ext,k        held over [k, k+1)
 *     xi_{k+1} = Phi xi_k + Gamma[:,0] x_r,k + Gamma[:,1] w_k
 * starting at rest at x_r,0 (xi_0 = xi0 x_r,0).
 *
 * The discretisation is computed here (vcnc_linalg.c's matrix exponential) whenever the
 * parameters differ from those the FMU was exported with; for the exported parameters the
 * matrices computed by scipy at export are used, so the FMU reproduces model.simulate() bit for
 * bit.
 *
 * Effects (optional, neutral at their defaults):
 *   delay    the model sees x_r,k-delay (a transport delay of the command, whole samples);
 *   backlash the measured position follows the linear position through a lost-motion element of
 *            total width `backlash` [mm].
 */
#ifndef VCNC_MODEL_H
#define VCNC_MODEL_H

#include <stddef.h>

#define VCNC_NX 3            /* states of the reduced model */
#define VCNC_MAX_DELAY 4096  /* longest input delay [samples] */

typedef struct {
    double a1, a2, a3;       /* denominator of Eq. 3.3: [1/s], [1/s^2], [1/s^3] */
    double b0, b1, b2;       /* numerator of Eq. 3.3: [1], [1/s], [1/s^2] */
    double d0, d1;           /* friction for positive / negative velocity [mm/s^2] */
    double sample_time;      /* [s] */
    double backlash;         /* lost motion, total width [mm]; 0 = none */
    int delay;               /* command delay [samples]; 0 = none */
} vcnc_parameters;

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
    /* state */
    double xi[VCNC_NX];
    double prev;                     /* model input of the previous sample [mm] */
    double play;             /* backlash: position of the load side [mm] */
    double history[VCNC_MAX_DELAY]; /* delay line of x_r, ring buffer */
    int head;
    /* inputs */
    double x_ref;            /* commanded position [mm] */
    double r0;               /* x_ref at initialisation [mm]: the loop runs on x_ref - r0 */
    double w_ext;            /* external disturbance [mm/s^2] */
} vcnc_model;

/* Continuous scaled realisation: A (3x3), B (3x2: columns x_r, w), C, D (position), Cv, Dv
 * (velocity, without its b0 dx_r/dt part); W the time scale [rad/s]. */
void vcnc_model_realise(const vcnc_parameters *p, double A[9], double B[6], double C[3], double D[2],
                        double Cv[3], double Dv[2], double *W);

/* Sample the model at p->sample_time. Returns 0, or -1 with a reason in msg. */
int vcnc_model_discretize(const vcnc_parameters *p, vcnc_discrete *dm, char *msg, size_t msg_size);

/* The parameters and discretisation embedded at export (vcnc_config.h). */
extern const vcnc_parameters vcnc_exported_parameters;
extern const vcnc_discrete vcnc_exported_discrete;

/* Check the parameters, discretise, and put the model at rest at the current x_ref.
 * Returns 0, or -1 with a reason in msg. */
int vcnc_model_initialize(vcnc_model *m, char *msg, size_t msg_size);

/* Measured position [mm] and tracking error x_ref - position [mm] for the current state and
 * inputs (direct feedthrough: reflects x_ref as soon as it is set). */
void vcnc_model_outputs(const vcnc_model *m, double *position, double *tracking_error);

/* Advance one sample with the current inputs held. */
void vcnc_model_step(vcnc_model *m);

#endif
