/* Small dense linear algebra for the vcnc axis model (see vcnc_linalg.h). */
#include "vcnc_linalg.h"

#include <math.h>
#include <string.h>

#define NMAX VCNC_LINALG_MAX

void vcnc_matmul(int n, const double *A, const double *B, double *C)
{
    int i, j, k;
    for (i = 0; i < n; i++) {
        for (j = 0; j < n; j++) {
            double s = 0.0;
            for (k = 0; k < n; k++) s += A[i * n + k] * B[k * n + j];
            C[i * n + j] = s;
        }
    }
}

int vcnc_solve(int n, int m, double *A, double *B)
{
    int i, j, k;
    for (k = 0; k < n; k++) {
        int p = k;
        double best = fabs(A[k * n + k]);
        for (i = k + 1; i < n; i++) {
            if (fabs(A[i * n + k]) > best) { best = fabs(A[i * n + k]); p = i; }
        }
        if (!(best > 0.0) || !isfinite(best)) return -1;
        if (p != k) {
            for (j = 0; j < n; j++) { double t = A[k * n + j]; A[k * n + j] = A[p * n + j]; A[p * n + j] = t; }
            for (j = 0; j < m; j++) { double t = B[k * m + j]; B[k * m + j] = B[p * m + j]; B[p * m + j] = t; }
        }
        for (i = k + 1; i < n; i++) {
            double f = A[i * n + k] / A[k * n + k];
            if (f == 0.0) continue;
            for (j = k; j < n; j++) A[i * n + j] -= f * A[k * n + j];
            for (j = 0; j < m; j++) B[i * m + j] -= f * B[k * m + j];
        }
    }
    for (k = n - 1; k >= 0; k--) {
        for (j = 0; j < m; j++) {
            double s = B[k * m + j];
            for (i = k + 1; i < n; i++) s -= A[k * n + i] * B[i * m + j];
            B[k * m + j] = s / A[k * n + k];
        }
    }
    return 0;
}

static double norm1(int n, const double *A)
{
    double best = 0.0;
    int i, j;
    for (j = 0; j < n; j++) {
        double s = 0.0;
        for (i = 0; i < n; i++) s += fabs(A[i * n + j]);
        if (s > best || s != s) best = s;
    }
    return best;
}

int vcnc_expm(int n, const double *A, double *E)
{
    /* Pade(13) coefficients b_0..b_13 (Higham 2005, Table 2.3). */
    static const double b[14] = {
        64764752532480000.0, 32382376266240000.0, 7771770303897600.0, 1187353796428800.0,
        129060195264000.0,   10559470521600.0,    670442572800.0,     33522128640.0,
        1323241920.0,        40840800.0,          960960.0,           16380.0,
        182.0,               1.0};
    const double theta13 = 5.371920351148152;
    double As[NMAX * NMAX], A2[NMAX * NMAX], A4[NMAX * NMAX], A6[NMAX * NMAX];
    double T1[NMAX * NMAX], T2[NMAX * NMAX], U[NMAX * NMAX], V[NMAX * NMAX];
    double P[NMAX * NMAX], Q[NMAX * NMAX];
    double nrm, scale;
    int i, s, nn = n * n;

    if (n < 1 || n > NMAX) return -1;
    nrm = norm1(n, A);
    if (!isfinite(nrm)) return -1;

    s = 0;
    if (nrm > theta13) s = (int)ceil(log2(nrm / theta13));
    if (s < 0) s = 0;
    scale = ldexp(1.0, -s);
    for (i = 0; i < nn; i++) As[i] = A[i] * scale;

    vcnc_matmul(n, As, As, A2);
    vcnc_matmul(n, A2, A2, A4);
    vcnc_matmul(n, A2, A4, A6);

    /* U = A [A6 (b13 A6 + b11 A4 + b9 A2) + b7 A6 + b5 A4 + b3 A2 + b1 I] */
    for (i = 0; i < nn; i++) T1[i] = b[13] * A6[i] + b[11] * A4[i] + b[9] * A2[i];
    vcnc_matmul(n, A6, T1, T2);
    for (i = 0; i < nn; i++) T2[i] += b[7] * A6[i] + b[5] * A4[i] + b[3] * A2[i];
    for (i = 0; i < n; i++) T2[i * n + i] += b[1];
    vcnc_matmul(n, As, T2, U);

    /* V = A6 (b12 A6 + b10 A4 + b8 A2) + b6 A6 + b4 A4 + b2 A2 + b0 I */
    for (i = 0; i < nn; i++) T1[i] = b[12] * A6[i] + b[10] * A4[i] + b[8] * A2[i];
    vcnc_matmul(n, A6, T1, V);
    for (i = 0; i < nn; i++) V[i] += b[6] * A6[i] + b[4] * A4[i] + b[2] * A2[i];
    for (i = 0; i < n; i++) V[i * n + i] += b[0];

    /* (V - U) R = (V + U) */
    for (i = 0; i < nn; i++) { Q[i] = V[i] - U[i]; P[i] = V[i] + U[i]; }
    if (vcnc_solve(n, n, Q, P) != 0) return -1;

    for (; s > 0; s--) {
        vcnc_matmul(n, P, P, T1);
        memcpy(P, T1, sizeof(double) * (size_t)nn);
    }
    for (i = 0; i < nn; i++) {
        if (!isfinite(P[i])) return -1;
        E[i] = P[i];
    }
    return 0;
}
