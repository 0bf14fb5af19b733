/* SPDX-License-Identifier: GPL-3.0-or-later */
/* emt: effective-medium (Walton / Digby-type) moduli of a random pack of identical Hertz
 * spheres (physics.md §13; Mavko, Mukerji & Dvorkin, The Rock Physics Handbook), to set
 * beside simulated moduli:
 *     K      = [ Z^2 (1-phi)^2 mu^2 P / (18 pi^2 (1-nu)^2) ]^(1/3)
 *     G_rough  = (5 - 4 nu) / (5 (2 - nu)) [ 3 Z^2 (1-phi)^2 mu^2 P / (2 pi^2 (1-nu)^2) ]^(1/3)
 *     G_smooth = 3/5 K
 * with mu, nu the grains' shear modulus and Poisson ratio, phi the porosity, Z the mean
 * coordination and P the confining pressure.  "rough": infinite friction, no slip;
 * "smooth": frictionless. */
#ifndef QUSGM_EMT_H
#define QUSGM_EMT_H

struct emt {
	double K, G_rough, G_smooth;
};

void emt_moduli(double mu_g, double nu, double phi, double Z, double P, struct emt *out);

#endif
