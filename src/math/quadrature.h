/* Gauss-Legendre quadrature nodes and weights, computed in double at plan creation. Internal. */
#ifndef HB_QUADRATURE_H
#define HB_QUADRATURE_H

/* n nodes x[k] and weights w[k] of the n-point Gauss-Legendre rule on [a, b]. */
void hb_gauss_legendre(int n, double a, double b, double *x, double *w);

#endif
