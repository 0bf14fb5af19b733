/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fr_lanes: the friction kernel on FR_LN contacts at once, included by friction.c once per
 * lane count (2: SSE2's v2d, fr_pair2; 4: AVX2's v4d, fr_pair4), so that both are one text.
 *
 * fr_contact_eval of FR_LN pairs under the return map, contact cs[L] in lane L, and with g
 * their gradients (fr_add_ij, or fr_add_i where j >= g1): lane by lane the same operations in
 * the same order (IEEE arithmetic on each lane, no contraction: lanes.h), so the same bytes;
 * both branches of each clamp are computed and one chosen by a mask, and the square roots are
 * one instruction for all lanes.  The scatter adds lane 0, then 1, ..., as calls of fr_add_ij
 * one contact after the other would.  Their energies into E.  The includer defines FR_LN,
 * FR_VD and FR_VM (the vector types), FR_SEL, FR_ABS, FR_SQRT, FR_CROSS (lanes.h's macros),
 * FR_FIELD(fld) (the vector of cs[L]->fld) and FR_AT(p, i) (of p[L][i]) written out lane by
 * lane (brace initialisers: GCC builds them better than a loop over the lanes, 5 % of the
 * increment), FR_ATTR (the function's attributes) and FR_NAME; they are undefined at the end. */
#ifdef FR_NAME	/* empty anywhere else (an installed header compiles alone) */
FR_ATTR void
FR_NAME(const struct qs_friction *f, const struct qs_system *s, double *g, size_t g1, struct fr_contact *const *cs,
    double *E)
{
	const double *gi[FR_LN], *gj[FR_LN];
	FR_VD du[3], wi[3], wj[3], n[3], v[3], us[3], t[3], q[3], sq[3], Q[3], x[3], dn, qq, qn, Ot, m, am, M, es, et, e;
	FR_VD k = FR_FIELD(k), kt = FR_FIELD(kt), qmax = FR_FIELD(qmax), mp = FR_FIELD(mp), mmax = FR_FIELD(mmax);
	FR_VD pp = FR_FIELD(pp), mpp = FR_FIELD(mpp), ai = FR_FIELD(ai), aj = FR_FIELD(aj), bi = FR_FIELD(bi);
	FR_VD bj = FR_FIELD(bj);
	FR_VM stick, tstick, mpos;
	int a, L;

	VEC3_UNROLL
	for (L = 0; L < FR_LN; L++) {
		gi[L] = f->gs + FR_GS * cs[L]->i;
		gj[L] = f->gs + FR_GS * (size_t)cs[L]->j;
	}
	VEC3_UNROLL
	for (a = 0; a < 3; a++) {
		du[a] = FR_AT(gi, a) - FR_AT(gj, a);
		wi[a] = FR_AT(gi, 3 + a);
		wj[a] = FR_AT(gj, 3 + a);
		n[a] = FR_FIELD(n[a]);
		v[a] = ai * wi[a] + aj * wj[a];
	}
	dn = du[0] * n[0] + du[1] * n[1] + du[2] * n[2];
	FR_CROSS(v, n, t);
	VEC3_UNROLL
	for (a = 0; a < 3; a++)
		us[a] = du[a] - dn * n[a] - t[a];
	VEC3_UNROLL
	for (a = 0; a < 3; a++)
		q[a] = FR_FIELD(qp[a]) - k * us[a];
	qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
	qn = FR_SQRT(qq);
	VEC3_UNROLL
	for (a = 0; a < 3; a++)
		sq[a] = qmax * q[a] / qn;
	/* the clamps: Q = q while it sticks, else Q_max q / |q|; M = m within its limit, else
	 * the limit with m's sign; the energies' clamp_potential */
	stick = qn <= qmax;
	VEC3_UNROLL
	for (a = 0; a < 3; a++)
		Q[a] = FR_SEL(stick, q[a], sq[a]);
	es = FR_SEL(stick, qn * qn, 2 * qmax * qn - qmax * qmax) - pp;
	Ot = bi * (wi[0] * n[0] + wi[1] * n[1] + wi[2] * n[2]) - bj * (wj[0] * n[0] + wj[1] * n[1] + wj[2] * n[2]);
	m = mp - kt * Ot;
	am = FR_ABS(m);
	tstick = am <= mmax;
	mpos = m > 0;
	M = FR_SEL(tstick, m, FR_SEL(mpos, mmax, -mmax));
	et = FR_SEL(tstick, am * am, 2 * mmax * am - mmax * mmax) - mpp;
	e = es / (2 * k) + et / (2 * kt);
	VEC3_UNROLL
	for (L = 0; L < FR_LN; L++) {
		struct fr_contact *c = cs[L];
		E[L] = e[L];
		c->qtrial = qn[L];
		VEC3_UNROLL
		for (a = 0; a < 3; a++)
			c->Q[a] = Q[a][L];
		c->M = M[L];
	}
	if (!g)
		return;
	/* the gradient (fr_add_ij's): n x Q, then on i ai (n x Q) - bi M n and -Q, on j
	 * aj (n x Q) + bj M n and Q */
	FR_CROSS(n, Q, x);
	{
		FR_VD mi = M * bi, mj = M * bj, gwi[3], gwj[3];
		double *gw = g + 3 * s->n;

		VEC3_UNROLL
		for (a = 0; a < 3; a++) {
			gwi[a] = ai * x[a] - mi * n[a];
			gwj[a] = aj * x[a] + mj * n[a];
		}
		for (L = 0; L < FR_LN; L++) {
			size_t i = cs[L]->i, j = (size_t)cs[L]->j;
			VEC3_UNROLL
			for (a = 0; a < 3; a++)
				g[3 * i + a] -= Q[a][L];
			VEC3_UNROLL
			for (a = 0; a < 3; a++)
				gw[3 * i + a] += gwi[a][L];
			if (j < g1) {
				VEC3_UNROLL
				for (a = 0; a < 3; a++)
					g[3 * j + a] += Q[a][L];
				VEC3_UNROLL
				for (a = 0; a < 3; a++)
					gw[3 * j + a] += gwj[a][L];
			}
		}
	}
}
/* the parameters undefined, for the next inclusion */
#undef FR_LN
#undef FR_VD
#undef FR_VM
#undef FR_SEL
#undef FR_ABS
#undef FR_SQRT
#undef FR_CROSS
#undef FR_FIELD
#undef FR_AT
#undef FR_ATTR
#undef FR_NAME
#endif
