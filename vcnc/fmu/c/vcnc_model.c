/* The vcnc reduced closed-loop axis model (see vcnc_model.h for the contract). */
#include "vcnc_model.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vcnc_linalg.h"

#define NX VCNC_NX

static int fail(char *msg, size_t msg_size, const char *text)
{
    if (msg && msg_size) {
        strncpy(msg, text, msg_size - 1);
        msg[msg_size - 1] = '\0';
    }
    return -1;
}

void vcnc_model_realise(const vcnc_parameters *p, double A[9], double B[6], double C[3], double D[2],
                        double Cv[3], double Dv[2], double *W_out)
{
    /* Scaling state i by W^(i-1) keeps A's entries of order W instead of a3 ~ 1e5..1e7. */
    double W = pow(p->a3, 1.0 / 3.0);
    double n2 = p->b1 - p->a1 * p->b0, n1 = p->b2 - p->a2 * p->b0, n0 = p->a3 * (1.0 - p->b0);
    double W2 = pow(W, 2.0);
    A[0] = -p->a1;      A[1] = W;   A[2] = 0.0;
    A[3] = -p->a2 / W;  A[4] = 0.0; A[5] = W;
    A[6] = -p->a3 / W2; A[7] = 0.0; A[8] = 0.0;
    B[0] = n2;          B[1] = 0.0;
    B[2] = n1 / W;      B[3] = -1.0 / W;
    B[4] = n0 / W2;     B[5] = 0.0;
    C[0] = 1.0;  C[1] = 0.0; C[2] = 0.0;
    D[0] = p->b0; D[1] = 0.0;
    Cv[0] = -p->a1; Cv[1] = W; Cv[2] = 0.0;
    Dv[0] = n2;  Dv[1] = 0.0;
    *W_out = W;
}

int vcnc_model_discretize(const vcnc_parameters *p, vcnc_discrete *dm, char *msg, size_t msg_size)
{
    enum { N = NX + 3 };
    double A[9], B[6], C[3], D[2], Cv[3], Dv[2], W, M[N * N], E[N * N], g0[NX], ramp[NX], z0[NX];
    double T = p->sample_time;
    int i, j;

    if (!(p->a3 > 0.0)) return fail(msg, msg_size, "parameter a3 [1/s^3] must be > 0 (a stable closed loop)");
    vcnc_model_realise(p, A, B, C, D, Cv, Dv, &W);

    /* expm([[A T, b_r T, 0, b_w T], [0, 0, 1, 0], [0, 0, 0, 0], [0, 0, 0, 0]]) */
    memset(M, 0, sizeof(M));
    for (i = 0; i < NX; i++) {
        for (j = 0; j < NX; j++) M[i * N + j] = A[i * NX + j] * T;
        M[i * N + 3] = B[i * 2 + 0] * T;
        M[i * N + 5] = B[i * 2 + 1] * T;
    }
    M[3 * N + 4] = 1.0;
    if (vcnc_expm(N, M, E) != 0) return fail(msg, msg_size, "matrix exponential failed (parameters not finite?)");

    for (i = 0; i < NX; i++) {
        for (j = 0; j < NX; j++) dm->phi[i * NX + j] = E[i * N + j];
        g0[i] = E[i * N + 3];
        ramp[i] = E[i * N + 4];
        dm->gamma[i * 2 + 1] = E[i * N + 5];
    }
    for (i = 0; i < NX; i++) {
        /* G0 - N + Phi N */
        double pn = (dm->phi[i * NX + 0] * ramp[0] + dm->phi[i * NX + 1] * ramp[1]) + dm->phi[i * NX + 2] * ramp[2];
        dm->gamma[i * 2 + 0] = (g0[i] - ramp[i]) + pn;
    }
    for (i = 0; i < NX; i++) {
        dm->c[i] = C[i];
        dm->cv[i] = Cv[i];
    }
    dm->d = D[0] + ((C[0] * ramp[0] + C[1] * ramp[1]) + C[2] * ramp[2]);
    dm->dv = Dv[0] + ((Cv[0] * ramp[0] + Cv[1] * ramp[1]) + Cv[2] * ramp[2]);
    dm->dvs = p->b0 / T;
    z0[0] = 1.0 - p->b0;
    z0[1] = (p->a1 - p->b1) / W;
    z0[2] = (p->a2 - p->b2) / pow(W, 2.0);
    for (i = 0; i < NX; i++) dm->xi0[i] = z0[i] - ramp[i];
    for (i = 0; i < NX * NX; i++) {
        if (!isfinite(dm->phi[i])) return fail(msg, msg_size, "the sampled model is not finite");
    }
    return 0;
}

static int check_parameters(const vcnc_parameters *p, char *msg, size_t msg_size)
{
    const double values[] = {p->a1, p->a2, p->a3, p->b0, p->b1, p->b2, p->d0, p->d1, p->sample_time, p->backlash};
    const char *names[] = {"a1", "a2", "a3", "b0", "b1", "b2", "d0", "d1", "sample_time", "backlash"};
    char text[160];
    size_t i;
    for (i = 0; i < sizeof(values) / sizeof(values[0]); i++) {
        if (!isfinite(values[i])) {
            snprintf(text, sizeof(text), "parameter %s is not finite", names[i]);
            return fail(msg, msg_size, text);
        }
    }
    if (!(p->sample_time > 0.0)) return fail(msg, msg_size, "parameter sample_time [s] must be > 0");
    if (!(p->a3 > 0.0)) return fail(msg, msg_size, "parameter a3 [1/s^3] must be > 0 (a stable closed loop)");
    if (p->backlash < 0.0) return fail(msg, msg_size, "parameter backlash [mm] must be >= 0");
    if (p->delay < 0 || p->delay > VCNC_MAX_DELAY) {
        snprintf(text, sizeof(text), "parameter delay_samples must be in [0, %d], got %d", VCNC_MAX_DELAY, p->delay);
        return fail(msg, msg_size, text);
    }
    return 0;
}

static int same_linear_model(const vcnc_parameters *a, const vcnc_parameters *b)
{
    return a->a1 == b->a1 && a->a2 == b->a2 && a->a3 == b->a3 && a->b0 == b->b0 && a->b1 == b->b1 &&
           a->b2 == b->b2 && a->sample_time == b->sample_time;
}

/* Position for the absolute reference u [mm]; the state lives in deviations from r0. */
static double linear_position(const vcnc_model *m, double u)
{
    const vcnc_discrete *dm = &m->dm;
    return (((dm->c[0] * m->xi[0] + dm->c[1] * m->xi[1]) + dm->c[2] * m->xi[2]) + dm->d * (u - m->r0)) + m->r0;
}

int vcnc_model_initialize(vcnc_model *m, char *msg, size_t msg_size)
{
    double u = m->x_ref, position, error;
    int i;
    if (check_parameters(&m->par, msg, msg_size) != 0) return -1;
    if (same_linear_model(&m->par, &vcnc_exported_parameters)) {
        m->dm = vcnc_exported_discrete;
        m->exported = 1;
    } else {
        if (vcnc_model_discretize(&m->par, &m->dm, msg, msg_size) != 0) return -1;
        m->exported = 0;
    }
    /* At rest: in deviations from r0 the state is exactly zero (v_0 == 0, no friction). */
    m->r0 = u;
    for (i = 0; i < NX; i++) m->xi[i] = 0.0;
    m->prev = 0.0;
    for (i = 0; i < m->par.delay; i++) m->history[i] = u;
    m->head = 0;
    m->play = linear_position(m, u);
    vcnc_model_outputs(m, &position, &error);
    if (!isfinite(position)) return fail(msg, msg_size, "the initial state is not finite");
    return 0;
}

static double model_input(const vcnc_model *m)
{
    return m->par.delay > 0 ? m->history[m->head] : m->x_ref;
}

static double lost_motion(const vcnc_model *m, double x)
{
    double half = 0.5 * m->par.backlash;
    if (half <= 0.0) return x;
    if (x - m->play > half) return x - half;
    if (x - m->play < -half) return x + half;
    return m->play;
}

void vcnc_model_outputs(const vcnc_model *m, double *position, double *tracking_error)
{
    double p = lost_motion(m, linear_position(m, model_input(m)));
    *position = p;
    *tracking_error = m->x_ref - p;
}

void vcnc_model_step(vcnc_model *m)
{
    const vcnc_discrete *dm = &m->dm;
    const double *phi = dm->phi, *g = dm->gamma, *xi = m->xi;
    double r = model_input(m) - m->r0;
    double v = (((dm->cv[0] * xi[0] + dm->cv[1] * xi[1]) + dm->cv[2] * xi[2]) + dm->dv * r) + dm->dvs * (r - m->prev);
    double f = v > 0.0 ? m->par.d0 : (v < 0.0 ? m->par.d1 : 0.0);
    double w = f + m->w_ext;
    double n0, n1, n2;

    if (m->par.backlash > 0.0) m->play = lost_motion(m, linear_position(m, r + m->r0));
    n0 = (((phi[0] * xi[0] + phi[1] * xi[1]) + phi[2] * xi[2]) + g[0] * r) + g[1] * w;
    n1 = (((phi[3] * xi[0] + phi[4] * xi[1]) + phi[5] * xi[2]) + g[2] * r) + g[3] * w;
    n2 = (((phi[6] * xi[0] + phi[7] * xi[1]) + phi[8] * xi[2]) + g[4] * r) + g[5] * w;
    m->xi[0] = n0;
    m->xi[1] = n1;
    m->xi[2] = n2;
    m->prev = r;
    if (m->par.delay > 0) {
        m->history[m->head] = m->x_ref;
        m->head = (m->head + 1) % m->par.delay;
    }
}
