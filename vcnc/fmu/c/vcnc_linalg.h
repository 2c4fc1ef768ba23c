/* Small dense linear algebra for the vcnc axis model: matrix exponential and helpers.
 *
 * Matrices are row-major arrays of doubles, n <= VCNC_LINALG_MAX. No allocation, no
 * dependency beyond libm, so the FMU binary needs nothing at run time.
 */
#ifndef VCNC_LINALG_H
#define VCNC_LINALG_H

#define VCNC_LINALG_MAX 8

/* C = A B (n x n); C may not alias A or B. */
void vcnc_matmul(int n, const double *A, const double *B, double *C);

/* Solve A X = B for X (n x n, m right-hand sides) by LU with partial pivoting; A and B are
 * overwritten (B holds X). Returns 0, or -1 if A is singular to working precision. */
int vcnc_solve(int n, int m, double *A, double *B);

/* E = expm(A) by scaling and squaring with the degree-13 Pade approximant (Higham 2005, the
 * algorithm of scipy.linalg.expm without its low-degree shortcuts). Returns 0, or -1 on failure
 * (non-finite input or a singular Pade denominator). */
int vcnc_expm(int n, const double *A, double *E);

#endif
