/* The vcnc reduced closed-loop axis model (see vcnc_model.h for the contract). */
#include "vcnc_model.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vcnc_linalg.h"

#define NX VCNC_NX
#define VCNC_PI 3.141592653589793
#define VCNC_SUBSTEPS 10 /* identification.augmented.SUBSTEPS */

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
    const double values[] = {p->a1, p->a2, p->a3, p->b0, p->b1, p->b2, p->d0, p->d1, p->sample_time,
                             p->stribeck[0], p->stribeck[1], p->stribeck[2], p->asym, p->pp_period,
                             p->tp_period, p->tp_mean, p->drift, p->viscous_rate, p->backlash,
                             p->res[0], p->res[1], p->res[2]};
    const char *names[] = {"a1", "a2", "a3", "b0", "b1", "b2", "d0", "d1", "sample_time",
                           "stribeck_velocity", "stribeck_excess_positive", "stribeck_excess_negative",
                           "viscous_asymmetry", "position_period", "time_period", "time_mean", "drift_rate",
                           "plant_viscous_rate", "backlash_width", "resonance_frequency", "resonance_damping",
                           "resonance_table_fraction"};
    char text[160];
    size_t i;
    int h;
    for (i = 0; i < sizeof(values) / sizeof(values[0]); i++) {
        if (!isfinite(values[i])) {
            snprintf(text, sizeof(text), "parameter %s is not finite", names[i]);
            return fail(msg, msg_size, text);
        }
    }
    for (h = 0; h < 2 * p->pp_harmonics; h++) {
        if (!isfinite(p->pp_coef[h])) return fail(msg, msg_size, "a position_periodic coefficient is not finite");
    }
    for (h = 0; h < 2 * p->tp_harmonics; h++) {
        if (!isfinite(p->tp_coef[h])) return fail(msg, msg_size, "a time_periodic coefficient is not finite");
    }
    if (!(p->sample_time > 0.0)) return fail(msg, msg_size, "parameter sample_time [s] must be > 0");
    if (!(p->ref_delay_s >= 0.0 && p->ref_delay_s / p->sample_time <= VCNC_MAX_REF_DELAY)) {
        snprintf(text, sizeof(text), "parameter reference_delay_s must be in [0, %d sample times], got %.17g s",
                 VCNC_MAX_REF_DELAY, p->ref_delay_s);
        return fail(msg, msg_size, text);
    }
    if (!(p->filter_s >= 0.0 && p->filter_s / p->sample_time <= VCNC_MAX_REF_DELAY)) {
        snprintf(text, sizeof(text), "parameter setpoint_filter_s must be in [0, %d sample times], got %.17g s",
                 VCNC_MAX_REF_DELAY, p->filter_s);
        return fail(msg, msg_size, text);
    }
    if (!(p->a3 > 0.0)) return fail(msg, msg_size, "parameter a3 [1/s^3] must be > 0 (a stable closed loop)");
    if (p->tp_on && !(p->tp_period > 0.0)) return fail(msg, msg_size, "parameter time_period [s] must be > 0");
    if (p->structured) {
        if (isnan(p->saturation)) return fail(msg, msg_size, "parameter saturation_limit is not a number");
        if (p->delay < 0 || p->delay > VCNC_MAX_DELAY) {
            snprintf(text, sizeof(text), "parameter delay_samples must be in [0, %d], got %d", VCNC_MAX_DELAY,
                     p->delay);
            return fail(msg, msg_size, text);
        }
        if (p->res[0] > 0.0 && !(p->res[2] > 0.0 && p->res[2] < 1.0)) {
            return fail(msg, msg_size, "parameter resonance_table_fraction must be in (0, 1)");
        }
    }
    return 0;
}

static int same_linear_model(const vcnc_parameters *a, const vcnc_parameters *b)
{
    return a->a1 == b->a1 && a->a2 == b->a2 && a->a3 == b->a3 && a->b0 == b->b0 && a->b1 == b->b1 &&
           a->b2 == b->b2 && a->sample_time == b->sample_time;
}

/* ------------------------------------------------------------------------- effects */

/* The velocity terms of identification.reduced_model.w_terms (Stribeck excess, asymmetric viscous). */
static double velocity_terms(const vcnc_parameters *p, double v)
{
    double w = 0.0;
    if (p->stribeck[0] > 0.0) {
        if (v > 0.0) {
            double r = v / p->stribeck[0];
            w += p->stribeck[1] * exp(-r * r);
        } else if (v < 0.0) {
            double r = v / p->stribeck[0];
            w += p->stribeck[2] * exp(-r * r);
        }
    }
    if (p->asym != 0.0) w += p->asym * fabs(v);
    return w;
}

/* w plus the position-periodic load at x, harmonic by harmonic (the order of w_terms). */
static double add_pp(const vcnc_parameters *p, double x, double w)
{
    int h;
    if (p->pp_period > 0.0) {
        double th = 2.0 * VCNC_PI * x / p->pp_period;
        for (h = 0; h < p->pp_harmonics; h++) {
            double a = (double)(h + 1) * th;
            w += p->pp_coef[2 * h] * sin(a) + p->pp_coef[2 * h + 1] * cos(a);
        }
    }
    return w;
}

/* identification.reduced_model.w_terms: the disturbance effects at velocity v, position x. */
static double w_terms(const vcnc_parameters *p, double v, double x)
{
    return add_pp(p, x, velocity_terms(p, v));
}

/* Disturbance known in time at sample k: the input w_ext plus the time_periodic load
 * (TimePeriodic.sampled_load: mean + sum_h C_h sin(h phi) + D_h cos(h phi), phi = 2 pi k T / P). */
static double wext(const vcnc_model *m)
{
    const vcnc_parameters *p = &m->par;
    double phase, load;
    int h;
    if (!p->tp_on) return m->w_ext;
    phase = 2.0 * VCNC_PI * (double)m->k * p->sample_time / p->tp_period;
    load = 0.0;
    for (h = 0; h < p->tp_harmonics; h++) {
        double a = phase * (double)(h + 1);
        load += sin(a) * p->tp_coef[2 * h];
        load += cos(a) * p->tp_coef[2 * h + 1];
    }
    return m->w_ext + (p->tp_mean + load);
}

/* Drift.pack: rate * t_k, t_k = k T. */
static double drift(const vcnc_model *m)
{
    return m->par.drift * ((double)m->k * m->par.sample_time);
}

/* -------------------------------------------------------------------------- exact form */

/* identification.dead_time.delay_reference: the reference the loop receives at sample k, x_ref
 * delayed by ref_delay samples with numpy.interp's arithmetic (numpy/_core/src/multiarray/
 * compiled_base.c, arr_interp: slope * (x - xp[j]) + fp[j], slope = (fp[j+1] - fp[j]) / 1.0); before
 * the record the first value is held. Past values come from the ring buffer rbuf. */
static double loop_ref(const vcnc_model *m)
{
    const double s = m->par.ref_delay;
    const int n = VCNC_MAX_REF_DELAY + 2;
    double xq, lo, hi;
    long long j;
    if (s == 0.0) return m->x_ref;
    xq = (double)m->k - s;
    if (xq <= 0.0) return m->k == 0 ? m->x_ref : m->rfirst;
    j = (long long)floor(xq);
    lo = m->rbuf[j % n];
    if ((double)j == xq) return lo;
    hi = j + 1 == m->k ? m->x_ref : m->rbuf[(j + 1) % n];
    return (hi - lo) * (xq - (double)j) + lo;
}

/* The delayed reference at sample i <= k (loop_ref) less the first one, x0: the current one at k, past ones
 * from the ring buffer lbuf, 0 at and before the first (identification.kernels.moving_average). */
static double delayed_at(const vcnc_model *m, long long i, double now, double x0)
{
    if (i <= 0) return 0.0;
    if (i == m->k) return now - x0;
    return m->lbuf[i % (VCNC_MAX_REF_DELAY + 2)] - x0;
}

/* identification.setpoint_filter.filter_reference: the loop's reference at sample k, the moving average of
 * the delayed reference over filter samples, in identification.kernels.moving_average's order of operations. */
static double input_ref(const vcnc_model *m)
{
    const double now = loop_ref(m), L = m->par.filter;
    const double x0 = m->k == 0 ? now : m->lfirst;
    long long n, i, j;
    double f, s = 0.0, lo, hi, mid;
    if (L == 0.0) return now;
    n = (long long)floor(L);
    f = L - (double)n;
    for (i = m->k - n; i < m->k; i++) {
        lo = delayed_at(m, i, now, x0);
        hi = delayed_at(m, i + 1, now, x0);
        s += (lo + hi) * 0.5;
    }
    if (f > 0.0) {
        j = m->k - n - 1;
        lo = delayed_at(m, j, now, x0);
        hi = delayed_at(m, j + 1, now, x0);
        mid = (hi - lo) * (1.0 - f) + lo;
        s += f * (hi + mid) * 0.5;
    }
    return s / L + x0;
}

/* Position for the absolute reference u [mm]; the state lives in deviations from r0. */
static double linear_position(const vcnc_model *m, double u)
{
    const vcnc_discrete *dm = &m->dm;
    return (((dm->c[0] * m->xi[0] + dm->c[1] * m->xi[1]) + dm->c[2] * m->xi[2]) + dm->d * (u - m->r0)) + m->r0;
}

static void exact_step(vcnc_model *m)
{
    const vcnc_discrete *dm = &m->dm;
    const double *phi = dm->phi, *g = dm->gamma, *xi = m->xi;
    const double ref = input_ref(m); /* the moving average costs a pass over its samples: taken once */
    double r = ref - m->r0;
    double v = (((dm->cv[0] * xi[0] + dm->cv[1] * xi[1]) + dm->cv[2] * xi[2]) + dm->dv * r) + dm->dvs * (r - m->prev);
    double f = v > 0.0 ? m->par.d0 : (v < 0.0 ? m->par.d1 : 0.0);
    double w = f + wext(m);
    double n0, n1, n2;

    w += w_terms(&m->par, v, linear_position(m, ref));
    n0 = (((phi[0] * xi[0] + phi[1] * xi[1]) + phi[2] * xi[2]) + g[0] * r) + g[1] * w;
    n1 = (((phi[3] * xi[0] + phi[4] * xi[1]) + phi[5] * xi[2]) + g[2] * r) + g[3] * w;
    n2 = (((phi[6] * xi[0] + phi[7] * xi[1]) + phi[8] * xi[2]) + g[4] * r) + g[5] * w;
    m->xi[0] = n0;
    m->xi[1] = n1;
    m->xi[2] = n2;
    m->prev = r;
}

/* -------------------------------------------------------------------------- split form */

static double split_measurement(const vcnc_model *m)
{
    const vcnc_parameters *p = &m->par;
    if (p->backlash > 0.0) return m->xb;
    return (p->res[0] > 0.0 && p->res[3] > 0.5) ? m->xt : m->xm;
}

/* identification.augmented._rigid: exact step of x'' = acc - c x' over h (acc held). */
static void rigid(double *x, double *v, double acc, double c, double h)
{
    double ch = c * h, e, p1, p2, x1, v1;
    if (ch < 1e-6) {
        e = 1.0 - ch;
        p1 = h * (1.0 - 0.5 * ch);
        p2 = h * h * (0.5 - ch / 6.0);
    } else {
        e = exp(-ch);
        p1 = -expm1(-ch) / c;
        p2 = (h - p1) / c;
    }
    x1 = *x + *v * p1 + acc * p2;
    v1 = *v * e + acc * p1;
    *x = x1;
    *v = v1;
}

/* identification.augmented._kinetic: friction while moving with velocity v != 0. */
static double kinetic(const vcnc_parameters *p, double v)
{
    return (v > 0.0 ? p->d0 : p->d1) + velocity_terms(p, v);
}

/* identification.augmented._friction_step: step h of mass x'' = force - F - c x' with friction F
 * that sticks (Karnopp) within the static levels [lo, hi]; lo >= hi switches on sign(v). */
static void friction_step(const vcnc_parameters *p, double *x, double *v, double force, double mass, double c,
                          double h, double lo, double hi)
{
    int stick = lo < hi;
    double f, dirn;
    if (*v == 0.0) {
        if (!stick) {
            f = 0.0;
            dirn = 0.0;
        } else if (force > hi) {
            f = hi;
            dirn = 1.0;
        } else if (force < lo) {
            f = lo;
            dirn = -1.0;
        } else {
            *v = 0.0;
            return;
        }
    } else {
        f = kinetic(p, *v);
        dirn = *v > 0.0 ? 1.0 : -1.0;
    }
    {
        double a = (force - f) / mass, x0 = *x, v0 = *v;
        rigid(x, v, a, c / mass, h);
        if (stick && *v * dirn < 0.0 && v0 != 0.0) {
            /* the motion stops inside the step: stick there, or break away for the rest */
            double cm = c / mass, ts = -v0 / (a - cm * v0);
            if (ts < 0.0) ts = 0.0;
            if (ts > h) ts = h;
            *x = x0 + v0 * ts + 0.5 * (a - cm * v0) * ts * ts;
            *v = 0.0;
            if (lo <= force && force <= hi) return;
            rigid(x, v, (force - (force > hi ? hi : lo)) / mass, cm, h - ts);
            return;
        }
        if (stick && *v * dirn < 0.0) *v = 0.0;
    }
}

/* identification.kernels._tm_slide: exact step of the sliding two-mass plant, D = [Ad | Bd] (4 x 6). */
static void tm_slide(const double *D, double s[4], double u, double g)
{
    double n[4];
    int i;
    for (i = 0; i < 4; i++) {
        const double *d = D + 6 * i;
        n[i] = d[0] * s[0] + d[1] * s[1] + d[2] * s[2] + d[3] * s[3] + d[4] * u + d[5] * g;
    }
    for (i = 0; i < 4; i++) s[i] = n[i];
}

/* identification.kernels._tm_substep: a substep of the two-mass plant with the table's friction
 * held (stiction at rest within [lo, hi]); s = (xm, vm, xt, vt). */
static void tm_substep(const vcnc_parameters *p, double kspr, double cdmp, double s[4], double u, double load,
                       double lo, double hi)
{
    int stick = lo < hi;
    double f, dirn;
    if (s[3] == 0.0) {
        double net = kspr * (s[0] - s[2]) + cdmp * s[1] - load;
        if (!stick) {
            f = 0.0;
            dirn = 0.0;
        } else if (net > hi) {
            f = hi;
            dirn = 1.0;
        } else if (net < lo) {
            f = lo;
            dirn = -1.0;
        } else {
            const double *S = p->tm + 48;
            double n0 = S[0] * s[0] + S[1] * s[1] + S[2] * u + S[3] * s[2];
            double n1 = S[6] * s[0] + S[7] * s[1] + S[8] * u + S[9] * s[2];
            s[0] = n0;
            s[1] = n1;
            s[3] = 0.0;
            return;
        }
    } else {
        f = kinetic(p, s[3]);
        dirn = s[3] > 0.0 ? 1.0 : -1.0;
    }
    tm_slide(p->tm, s, u, f + load);
    if (stick && s[3] * dirn < 0.0) s[3] = 0.0;
}

/* identification.augmented.two_mass_matrices, with vcnc_expm. */
static int two_mass_matrices(vcnc_parameters *p, char *msg, size_t msg_size)
{
    double om = 2.0 * VCNC_PI * p->res[0], zeta = p->res[1], r = p->res[2];
    double ks_m = om * om * r, cs_m = 2.0 * zeta * om * r;
    double ks_t = om * om * (1.0 - r), cs_t = 2.0 * zeta * om * (1.0 - r);
    double A[36], M[36], E[36], S[16], SM[16], SE[16], h = p->sample_time / p->substeps;
    int i, j, k;
    memset(A, 0, sizeof(A));
    memset(S, 0, sizeof(S));
    A[0 * 6 + 1] = 1.0;
    A[1 * 6 + 0] = -ks_m;
    A[1 * 6 + 1] = -cs_m;
    A[1 * 6 + 2] = ks_m;
    A[1 * 6 + 3] = cs_m;
    A[1 * 6 + 4] = 1.0 / (1.0 - r);
    A[2 * 6 + 3] = 1.0;
    A[3 * 6 + 0] = ks_t;
    A[3 * 6 + 1] = cs_t;
    A[3 * 6 + 2] = -ks_t;
    A[3 * 6 + 3] = -cs_t - p->viscous_rate / r;
    A[3 * 6 + 5] = -1.0 / r;
    S[0 * 4 + 1] = 1.0;
    S[1 * 4 + 0] = -ks_m;
    S[1 * 4 + 1] = -cs_m;
    S[1 * 4 + 2] = 1.0 / (1.0 - r);
    S[1 * 4 + 3] = ks_m;
    memset(p->tm, 0, sizeof(p->tm));
    for (k = 0; k < 2; k++) {
        double t = k == 0 ? h : p->sample_time;
        for (i = 0; i < 36; i++) M[i] = A[i] * t;
        if (vcnc_expm(6, M, E) != 0) return fail(msg, msg_size, "matrix exponential of the two-mass plant failed");
        for (i = 0; i < 4; i++)
            for (j = 0; j < 6; j++) p->tm[24 * k + 6 * i + j] = E[6 * i + j];
    }
    for (i = 0; i < 16; i++) SM[i] = S[i] * h;
    if (vcnc_expm(4, SM, SE) != 0) return fail(msg, msg_size, "matrix exponential of the two-mass plant failed");
    for (i = 0; i < 2; i++)
        for (j = 0; j < 4; j++) p->tm[48 + 6 * i + j] = SE[4 * i + j];
    return 0;
}

/* identification.kernels._play: the load side xb follows the driven side within +/- half. */
static double play(double mech, double xb, double half)
{
    if (mech - xb > half) return mech - half;
    if (mech - xb < -half) return mech + half;
    return xb;
}

static void split_step(vcnc_model *m)
{
    const vcnc_parameters *p = &m->par;
    const double T = p->sample_time, a1 = p->a1, a2 = p->a2, a3 = p->a3, cvis = p->viscous_rate;
    const int steps = p->substeps, two_mass = p->res[0] > 0.0, meas_table = p->res[3] > 0.5;
    const double h = T / steps, kd = a1 - cvis, ff = p->b2 - a2, rr = p->res[2], bl = p->backlash;
    const double xr = input_ref(m);
    double kspr = 0.0, cdmp = 0.0, y, e, vr, ar, u, lo, hi, we, s4[4] = {0.0, 0.0, 0.0, 0.0};
    const double vguard = p->stribeck[0] > 0.0 ? 3.0 * p->stribeck[0] : 0.0;
    int i, n_steps;
    if (two_mass) {
        double om = 2.0 * VCNC_PI * p->res[0];
        kspr = om * om * rr * (1.0 - rr);
        cdmp = 2.0 * p->res[1] * om * rr * (1.0 - rr);
    }
    /* sampled controller (Eq. 3.3 split) */
    y = split_measurement(m);
    e = xr - y;
    m->integ += T * e;
    vr = (xr - m->rprev) / T;
    ar = m->k > 1 ? (vr - m->vrprev) / T : 0.0;
    u = p->b1 * vr - kd * (y - m->yprev) / T + a2 * e + a3 * m->integ + ff * xr + p->b0 * ar - m->held;
    /* conditional integration of the saturation element's anti-windup (identification.kernels.run_split):
     * no accumulator step that drives a demand beyond the limit further out */
    if (p->anti_windup) {
        double step = a3 * (T * e + p->integral_lead * (e - m->eprev)) + ff * (xr - m->rprev);
        if ((u > p->saturation || u < -p->saturation) && step * u > 0.0) {
            m->held += step;
            u -= step;
        }
        m->eprev = e;
    }
    m->yprev = y;
    m->rprev = xr;
    m->vrprev = vr;
    if (p->delay > 0) {
        int n = p->delay + 1;
        m->ubuf[m->k % n] = u;
        u = m->k >= p->delay ? m->ubuf[(m->k + 1) % n] : 0.0;
    }
    if (u > p->saturation) {
        u = p->saturation;
    } else if (u < -p->saturation) {
        u = -p->saturation;
    }
    /* plant over the sample (u held); friction sticks within the static levels */
    lo = p->d1 + (p->stribeck[0] > 0.0 ? p->stribeck[2] : 0.0);
    hi = p->d0 + (p->stribeck[0] > 0.0 ? p->stribeck[1] : 0.0);
    we = wext(m);
    n_steps = steps;
    if (two_mass) {
        s4[0] = m->xm;
        s4[1] = m->vm;
        s4[2] = m->xt;
        s4[3] = m->vt;
    }
    /* a whole-sample step while friction is constant over it (identification.kernels.run_split) */
    if (two_mass && bl <= 0.0 && p->asym == 0.0 && p->pp_period <= 0.0 && fabs(m->vt) > vguard) {
        double n4[4] = {s4[0], s4[1], s4[2], s4[3]};
        tm_slide(p->tm + 24, n4, u, kinetic(p, m->vt) + we);
        if (n4[3] * m->vt > 0.0 && fabs(n4[3]) > vguard) {
            for (i = 0; i < 4; i++) s4[i] = n4[i];
            n_steps = 0;
        }
    } else if (!two_mass && steps > 1 && p->asym == 0.0 && p->pp_period <= 0.0 && fabs(m->vm) > vguard) {
        double x1 = m->xm, v1 = m->vm;
        friction_step(p, &x1, &v1, u - we, 1.0, cvis, T, lo, hi);
        if (v1 * m->vm > 0.0 && fabs(v1) > vguard) {
            m->xm = x1;
            m->vm = v1;
            n_steps = 0;
            if (bl > 0.0) m->xb = play(m->xm, m->xb, 0.5 * bl);
        }
    }
    for (i = 0; i < n_steps; i++) {
        double load = we + add_pp(p, two_mass ? s4[2] : m->xm, 0.0);
        if (two_mass) {
            tm_substep(p, kspr, cdmp, s4, u, load, lo, hi);
        } else {
            friction_step(p, &m->xm, &m->vm, u - load, 1.0, cvis, h, lo, hi);
        }
        if (bl > 0.0) m->xb = play(two_mass ? (meas_table ? s4[2] : s4[0]) : m->xm, m->xb, 0.5 * bl);
    }
    if (two_mass) {
        m->xm = s4[0];
        m->vm = s4[1];
        m->xt = s4[2];
        m->vt = s4[3];
    }
}

/* ------------------------------------------------------------------------- the model */

int vcnc_model_initialize(vcnc_model *m, char *msg, size_t msg_size)
{
    double u = m->x_ref, position, error;
    vcnc_parameters *p = &m->par;
    int i;
    if (check_parameters(p, msg, msg_size) != 0) return -1;
    m->k = 0;
    m->r0 = u;
    p->ref_delay = p->ref_delay_s / p->sample_time;
    p->filter = p->filter_s / p->sample_time;
    if (p->structured) {
        /* augmented.simulate_augmented: steps only for the play operator and the two-mass plant */
        p->substeps = (p->res[0] <= 0.0 && p->backlash <= 0.0) ? 1 : VCNC_SUBSTEPS;
        if (p->res[0] > 0.0) {
            const vcnc_two_mass *x = &vcnc_exported_two_mass;
            if (x->f == p->res[0] && x->zeta == p->res[1] && x->r == p->res[2] &&
                x->viscous_rate == p->viscous_rate && x->sample_time == p->sample_time && x->substeps == p->substeps) {
                memcpy(p->tm, x->tm, sizeof(p->tm)); /* computed by scipy at export: bit-exact */
            } else if (two_mass_matrices(p, msg, msg_size) != 0) {
                return -1;
            }
        }
        m->xm = u;
        m->vm = 0.0;
        m->xt = u;
        m->vt = 0.0;
        m->xb = u;
        m->integ = -(p->b2 - p->a2) * u / p->a3;
        m->held = 0.0;
        m->eprev = 0.0;
        for (i = 0; i <= VCNC_MAX_DELAY; i++) m->ubuf[i] = 0.0;
        m->yprev = u;
        m->rprev = u;
        m->vrprev = 0.0;
    } else {
        if (same_linear_model(p, &vcnc_exported_parameters)) {
            m->dm = vcnc_exported_discrete;
            m->exported = 1;
        } else {
            if (vcnc_model_discretize(p, &m->dm, msg, msg_size) != 0) return -1;
            m->exported = 0;
        }
        /* At rest: in deviations from r0 the state is exactly zero (v_0 == 0, no friction). */
        for (i = 0; i < NX; i++) m->xi[i] = 0.0;
        m->prev = 0.0;
    }
    vcnc_model_outputs(m, &position, &error);
    if (!isfinite(position)) return fail(msg, msg_size, "the initial state is not finite");
    return 0;
}

void vcnc_model_outputs(const vcnc_model *m, double *position, double *tracking_error)
{
    double pos = m->par.structured ? split_measurement(m) : linear_position(m, input_ref(m));
    if (m->par.drift != 0.0) pos = pos + drift(m);
    *position = pos;
    *tracking_error = m->x_ref - pos;
}

void vcnc_model_step(vcnc_model *m)
{
    const double delayed = loop_ref(m); /* before the step: the delayed reference of sample k */
    if (m->par.structured) {
        split_step(m);
    } else {
        exact_step(m);
    }
    if (m->k == 0) {
        m->rfirst = m->x_ref;
        m->lfirst = delayed;
    }
    m->rbuf[m->k % (VCNC_MAX_REF_DELAY + 2)] = m->x_ref;
    m->lbuf[m->k % (VCNC_MAX_REF_DELAY + 2)] = delayed;
    m->k++;
}

int vcnc_model_diverged(const vcnc_model *m)
{
    if (m->par.structured) return !(fabs(m->xm) < 1e9 && fabs(m->vm) < 1e12);
    return !isfinite(m->xi[0]) || !isfinite(m->xi[1]) || !isfinite(m->xi[2]);
}
