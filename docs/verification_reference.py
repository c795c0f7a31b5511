#!/usr/bin/env python3
"""Analytic reference values for the interface verification suite.

Every number quoted in docs/verification.md and every "expected" block in verification/cases/*.json
comes from this script. It uses the Python standard library only (math, cmath, json) and none of
petroscope's code, so it is an independent reference for the interface solver.

    python3 docs/verification_reference.py                      # print every value (15 significant digits)
    python3 docs/verification_reference.py --write-cases DIR    # also (re)write the JSON cases into DIR
    python3 docs/verification_reference.py --markdown           # only the tables of docs/verification.md

Methods (all closed forms; docs/verification.md derives them):
  * isotropic interfaces: Fresnel's formulae (Born & Wolf, Principles of Optics, 7th ed., §1.5.2-1.5.4);
  * a medium with one principal axis along y (isotropic; uniaxial with the optic axis in the plane of
    incidence x-z; biaxial with the optic axial plane x-z): the TE (E along y) and TM (H along y) waves
    decouple; each has a closed-form normal component q = k_z/k0 and a closed-form admittance, and the
    interface is two 2x2 problems (section "TE/TM" below);
  * an optically active uniaxial crystal (quartz) with its optic axis along the normal, at normal incidence:
    Landau's relation D = eps E + i (g.N) x E gives two circular waves with n^2 = n_o^2 +- n g33, and
    Berreman's bianisotropic form of it (H = N x E + i kappa E, kappa = (tr g/2) I - g) gives both of them
    the admittance n_bar = sqrt(n_o^2 + g33^2/4), so the interface is Fresnel's at normal incidence with
    n_bar (section "Optical activity" below);
  * otherwise (uniaxial at a general azimuth, and a biaxial crystal with the wave normal exactly on a
    binormal): the transmitted eigenmodes are written down in closed form (uniaxial: the ordinary sphere
    and the extraordinary ellipsoid, a quadratic in q; binormal: N = n_beta * b, any D perpendicular to b)
    and the four boundary conditions (tangential E and H continuous, Born & Wolf §1.1.3) are solved as a
    4x4 complex linear system by Gaussian elimination.

Conventions (verification/cases/README.md): fields ~ exp(i(k.r - w t)); the interface normal is +z, from
medium 1 into medium 2; the plane of incidence is x-z; s_hat = normalize(normal x k_hat) (normal x x_hat at
normal incidence), p_hat = s_hat x k_hat; Jones vectors (E_s, E_p); Stokes S0 = |E_s|^2 + |E_p|^2,
S1 = |E_s|^2 - |E_p|^2, S2 = 2 Re(E_s E_p*), S3 = -2 Im(E_s E_p*) (S3 > 0: right-handed in Born & Wolf's
sense), scaled so that S0 = the wave's power. H is in units of sqrt(eps0/mu0), so H = N x E with N = k/k0,
and the power of a wave is its Poynting flux along the normal relative to the incident one.
"""

import cmath
import json
import math
import os
import sys

DEG = math.pi / 180.0
WAVELENGTH_NM = 589.3


def g(x):
    """15 significant digits; complex numbers as a+bi."""
    if isinstance(x, complex):
        if x.imag == 0.0:
            return "%.15g" % x.real
        return "%.15g%+.15gi" % (x.real, x.imag)
    return "%.15g" % x


def out(label, *values):
    print("  %-58s %s" % (label, "  ".join(v if isinstance(v, str) else g(v) for v in values)))


# ----------------------------------------------------------------------------------------------------
# Small complex 3-vector and 3x3 matrix helpers (lists).

def add(a, b): return [a[i] + b[i] for i in range(3)]
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def scale(s, a): return [s * a[i] for i in range(3)]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))  # bilinear (no conjugation)
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def norm(a): return math.sqrt(sum(abs(a[i]) ** 2 for i in range(3)))
def unit(a): return scale(1.0 / norm(a), a)
def matvec(m, v): return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]
def matmul(a, b): return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def transpose(m): return [[m[j][i] for j in range(3)] for i in range(3)]
def real3(a): return [complex(a[i]).real for i in range(3)]


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]


def rot_y(b):
    c, s = math.cos(b), math.sin(b)
    return [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]


def euler_zyz_deg(a, b, c):
    """R = Rz(a) Ry(b) Rz(c), active right-handed rotations; columns = indicatrix axes X, Y, Z in the lab."""
    return matmul(matmul(rot_z(a * DEG), rot_y(b * DEG)), rot_z(c * DEG))


def zyz_from_matrix_deg(r):
    """The ZYZ Euler angles (degrees) of a rotation matrix with sin(b) != 0."""
    b = math.acos(max(-1.0, min(1.0, r[2][2])))
    a = math.atan2(r[1][2], r[0][2])
    c = math.atan2(r[2][1], -r[2][0])
    return [a / DEG, b / DEG, c / DEG]


def eta_lab(principal_n, r):
    """Impermeability eta = eps^-1 in the lab frame: R diag(1/n_i^2) R^T."""
    d = [[(1.0 / principal_n[i] ** 2 if i == j else 0.0) for j in range(3)] for i in range(3)]
    return matmul(matmul(r, d), transpose(r))


def eps_lab(principal_n, r):
    d = [[(principal_n[i] ** 2 if i == j else 0.0) for j in range(3)] for i in range(3)]
    return matmul(matmul(r, d), transpose(r))


def solve_linear(a, b):
    """Gaussian elimination with partial pivoting for a small complex system a x = b."""
    n = len(b)
    m = [list(a[i]) + [b[i]] for i in range(n)]
    for col in range(n):
        piv = max(range(col, n), key=lambda i: abs(m[i][col]))
        m[col], m[piv] = m[piv], m[col]
        for i in range(col + 1, n):
            f = m[i][col] / m[col][col]
            for j in range(col, n + 1):
                m[i][j] -= f * m[col][j]
    x = [0j] * n
    for i in range(n - 1, -1, -1):
        x[i] = (m[i][n] - sum(m[i][j] * x[j] for j in range(i + 1, n))) / m[i][i]
    return x


def sqrt_decaying(z):
    """sqrt with the evanescent branch Im >= 0 (fields ~ exp(i k0 q z) decay toward +z)."""
    z = complex(z)
    if z.imag == 0.0:
        return complex(math.sqrt(z.real), 0.0) if z.real >= 0.0 else complex(0.0, math.sqrt(-z.real))
    w = cmath.sqrt(z)
    return w if w.imag >= 0.0 else -w


# ----------------------------------------------------------------------------------------------------
# Polarization bases and Stokes vectors.

Z_HAT = [0.0, 0.0, 1.0]


def sp_basis(k_hat, normal=Z_HAT):
    """s_hat = normalize(normal x k_hat) (normal x x_hat at normal incidence), p_hat = s_hat x k_hat."""
    s = cross(normal, k_hat)
    if norm(s) == 0.0:
        s = cross(normal, [1.0, 0.0, 0.0])
        if norm(s) == 0.0:
            s = cross(normal, [0.0, 1.0, 0.0])
    s = unit(s)
    return s, cross(s, k_hat)


def stokes(es, ep):
    return [abs(es) ** 2 + abs(ep) ** 2, abs(es) ** 2 - abs(ep) ** 2, 2.0 * (es * ep.conjugate()).real,
            -2.0 * (es * ep.conjugate()).imag]


def flux_z(e, h):
    """Normal component of Re(E x H*) (the factor 1/2 of the time average cancels in every ratio)."""
    return (e[0] * h[1].conjugate() - e[1] * h[0].conjugate()).real


# ----------------------------------------------------------------------------------------------------
# Isotropic Fresnel formulae (Born & Wolf §1.5.2; docs/theory.md §3).

def fresnel(n1, n2, theta1):
    c1 = math.cos(theta1)
    xi = n1 * math.sin(theta1)
    q2 = sqrt_decaying(n2 * n2 - xi * xi)  # n2 cos(theta2), +i*sqrt(...) beyond the critical angle
    c2 = q2 / n2
    rs = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2)
    rp = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2)
    ts = 2 * n1 * c1 / (n1 * c1 + n2 * c2)
    tp = 2 * n1 * c1 / (n2 * c1 + n1 * c2)
    factor = (n2 * c2).real / (n1 * c1)  # Re(n2 cos theta2): zero under total internal reflection
    return {"rs": rs, "rp": rp, "ts": ts, "tp": tp, "Rs": abs(rs) ** 2, "Rp": abs(rp) ** 2,
            "Ts": factor * abs(ts) ** 2, "Tp": factor * abs(tp) ** 2, "cos2": c2, "xi": xi, "q2": q2}


def tir_phase(nrel, theta):
    """Born & Wolf §1.5.4: tan(delta/2) = cos(theta) sqrt(sin^2 theta - n^2) / sin^2 theta, n = n2/n1."""
    s2 = math.sin(theta) ** 2
    return 2.0 * math.atan(math.cos(theta) * math.sqrt(s2 - nrel * nrel) / s2)


# ----------------------------------------------------------------------------------------------------
# TE/TM decoupled interface: both media have a principal axis along y (eta_xy = eta_yz = 0).
#   TE (E = E_y y_hat):  q^2 = eps_yy - xi^2,            H_x = -q E_y,        flux ~ Re(q) |E_y|^2
#   TM (H = H_y y_hat):  eta_xx q^2 - 2 eta_xz xi q + eta_zz xi^2 = 1,
#                        E_x = e H_y with e = eta_xx q - eta_xz xi,           flux ~ Re(e) |H_y|^2
# (from N x E = H and N x H = -D with N = (xi, 0, q); derivation in docs/verification.md).

def te_roots(eta, xi):
    q = sqrt_decaying(1.0 / eta[1][1] - xi * xi)
    return q, -q  # forward (Re q > 0 or Im q > 0), backward


def tm_roots(eta, xi):
    """Roots of eta_xx q^2 - 2 b q + c = 0 (b = eta_xz xi, c = eta_zz xi^2 - 1): forward (e > 0 or Im q > 0), backward.

    e = eta_xx q - eta_xz xi = +-sqrt(disc); the root that would cancel is taken from the product c/eta_xx."""
    exx = eta[0][0]
    b = eta[0][2] * xi
    c = eta[2][2] * xi * xi - 1.0
    root = sqrt_decaying(b * b - exx * c)
    qf = (b + root) / exx if b >= 0.0 else c / (b - root)
    qb = (b - root) / exx if b <= 0.0 else c / (b + root)
    return qf, qb


def tm_e(eta, xi, q):
    return eta[0][0] * q - eta[0][2] * xi


def tm_ray(eta, xi, q):
    """Direction of Re(E x H*) for a propagating TM wave: (eta_zz xi - eta_xz q, 0, eta_xx q - eta_xz xi)."""
    return unit([eta[2][2] * xi - eta[0][2] * q.real, 0.0, eta[0][0] * q.real - eta[0][2] * xi])


def tetm_interface(eta1, eta2, xi):
    """Amplitude ratios and powers for a forward TE or TM wave in medium 1 meeting medium 2."""
    q1f, q1b = te_roots(eta1, xi)
    q2f, _ = te_roots(eta2, xi)
    r_te = (q1f - q2f) / (q1f + q2f)  # E_y ratios
    t_te = 1.0 + r_te
    te = {"r": r_te, "t": t_te, "q1": q1f, "q1b": q1b, "q2": q2f,
          "R": -q1b.real * abs(r_te) ** 2 / q1f.real, "T": q2f.real * abs(t_te) ** 2 / q1f.real}
    p1f, p1b = tm_roots(eta1, xi)
    p2f, _ = tm_roots(eta2, xi)
    e1f, e1b, e2f = tm_e(eta1, xi, p1f), tm_e(eta1, xi, p1b), tm_e(eta2, xi, p2f)
    a_r = (e2f - e1f) / (e1b - e2f)  # H_y ratios
    a_t = 1.0 + a_r
    tm = {"r": a_r, "t": a_t, "q1": p1f, "q1b": p1b, "q2": p2f, "e1": e1f, "e1b": e1b, "e2": e2f,
          "R": -e1b.real * abs(a_r) ** 2 / e1f.real, "T": e2f.real * abs(a_t) ** 2 / e1f.real}
    return te, tm


def mode_residual(eps, n_vec, e_vec):
    """|N x (N x E) + eps E| / |E|: zero for a plane-wave solution of Maxwell's equations."""
    r = add(cross(n_vec, cross(n_vec, e_vec)), matvec(eps, e_vec))
    return norm(r) / norm(e_vec)


# ----------------------------------------------------------------------------------------------------
# Explicit transmitted modes and the general 4x4 boundary problem (isotropic medium 1).

def uniaxial_modes(n_o, n_e, axis, xi_vec):
    """Forward ordinary and extraordinary modes for tangential xi_vec = (xi_x, xi_y)."""
    xx, xy = xi_vec
    eta = [[(1.0 / n_o ** 2) * (i == j) + (1.0 / n_e ** 2 - 1.0 / n_o ** 2) * axis[i] * axis[j] for j in range(3)]
           for i in range(3)]
    qo = sqrt_decaying(n_o ** 2 - xx * xx - xy * xy)
    n_vec_o = [xx, xy, qo]
    d_o = unit(cross(n_vec_o, axis))
    # extraordinary: (N.c)^2/n_o^2 + (N.N - (N.c)^2)/n_e^2 = 1, N = (xi_x, xi_y, q)
    u, w = 1.0 / n_o ** 2 - 1.0 / n_e ** 2, 1.0 / n_e ** 2
    a_t = xx * axis[0] + xy * axis[1]
    qa = u * axis[2] ** 2 + w
    qb = 2.0 * u * a_t * axis[2]
    qc = u * a_t * a_t + w * (xx * xx + xy * xy) - 1.0
    qe = (-qb + sqrt_decaying(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)  # forward: the larger root (qa > 0)
    n_vec_e = [xx, xy, qe]
    d_e = unit(cross(n_vec_e, cross(n_vec_e, axis)))
    modes = []
    for name, n_vec, d in (("ordinary", n_vec_o, d_o), ("extraordinary", n_vec_e, d_e)):
        e = matvec(eta, d)
        modes.append({"mode": name, "N": n_vec, "D": d, "E": e, "H": cross(n_vec, e)})
    return modes, eta


def solve_explicit(n1, k_in, jones, modes):
    """Unknowns (r_s, r_p, a_1, a_2); tangential E and H continuous at z = 0 (Born & Wolf §1.1.3)."""
    s_i, p_i = sp_basis(k_in)
    e_i = add(scale(jones[0], s_i), scale(jones[1], p_i))
    h_i = scale(n1, cross(k_in, e_i))
    k_r = [k_in[0], k_in[1], -k_in[2]]
    s_r, p_r = sp_basis(k_r)
    cols = [(s_r, scale(n1, cross(k_r, s_r))), (p_r, scale(n1, cross(k_r, p_r)))]
    cols += [(scale(-1.0, m["E"]), scale(-1.0, m["H"])) for m in modes]
    a = [[c[0][comp] for c in cols] for comp in (0, 1)] + [[c[1][comp] for c in cols] for comp in (0, 1)]
    b = [-e_i[0], -e_i[1], -h_i[0], -h_i[1]]
    x = solve_linear(a, b)
    inc = flux_z(e_i, h_i)
    e_t = [sum(x[2 + m] * modes[m]["E"][i] for m in range(2)) for i in range(3)]
    h_t = [sum(x[2 + m] * modes[m]["H"][i] for m in range(2)) for i in range(3)]
    return {"rs": x[0], "rp": x[1], "a": x[2:], "R": abs(x[0]) ** 2 + abs(x[1]) ** 2,
            "T_modes": [abs(x[2 + m]) ** 2 * flux_z(modes[m]["E"], modes[m]["H"]) / inc for m in range(2)],
            "T_total": flux_z(e_t, h_t) / inc}


# ----------------------------------------------------------------------------------------------------
# Crystals.

def biaxial_vz(n_alpha, n_beta, n_gamma):
    """Angle of the binormals from Z: tan^2 Vz = (a - b)/(b - c), a = n_alpha^-2 ... (docs/theory.md §1; Born & Wolf §15.3.3)."""
    a, b, c = n_alpha ** -2, n_beta ** -2, n_gamma ** -2
    return math.atan(math.sqrt((a - b) / (b - c)))


def ne_theta(n_o, n_e, theta):
    """Index of the extraordinary wave whose normal makes theta with the optic axis (Born & Wolf §15.3.2)."""
    return 1.0 / math.sqrt(math.cos(theta) ** 2 / n_o ** 2 + math.sin(theta) ** 2 / n_e ** 2)


def walkoff(n_o, n_e, theta):
    """tan(alpha) = 1/2 n_e(theta)^2 sin(2 theta) (1/n_e^2 - 1/n_o^2) (Yariv & Yeh §4.3)."""
    n = ne_theta(n_o, n_e, theta)
    return math.atan(0.5 * n * n * math.sin(2 * theta) * (1.0 / n_e ** 2 - 1.0 / n_o ** 2))


def ghosh_calcite(lam_um):
    """minerals/calcite.txt: rii-formula-2, n^2 - 1 = C1 + C2 L^2/(L^2 - C3) + C4 L^2/(L^2 - C5) (Ghosh 1999)."""
    def f(c1, c2, c3, c4, c5):
        l2 = lam_um * lam_um
        return math.sqrt(1.0 + c1 + c2 * l2 / (l2 - c3) + c4 * l2 / (l2 - c5))
    return f(0.73358749, 0.96464345, 1.94325203e-2, 1.82831454, 120.0), \
        f(0.35859695, 0.82427830, 1.06689543e-2, 0.14429128, 120.0)


def cauchy(a, b, lam_um):
    return a + b / (lam_um * lam_um)


def kato_ktp(lam_um):
    """minerals/ktp.txt: rii-formula-4, n^2 = C1 + C2 L^C3/(L^2 - C4^C5) + C6 L^C7/(L^2 - C8^C9) (Kato 2002)."""
    def f(c1, c2, c3, c4, c5, c6, c7, c8, c9):
        l2 = lam_um * lam_um
        return math.sqrt(c1 + c2 * lam_um ** c3 / (l2 - c4 ** c5) + c6 * lam_um ** c7 / (l2 - c8 ** c9))
    return (f(3.29100, 0.04140, 0, 0.03978, 1, 9.35522, 0, 31.45571, 1),
            f(3.45018, 0.04341, 0, 0.04597, 1, 16.98825, 0, 39.43799, 1),
            f(4.59423, 0.06206, 0, 0.04763, 1, 110.80672, 0, 86.12171, 1))


def ghosh_quartz(lam_um):
    """minerals/quartz.txt: n_o by rii-formula-2 (Ghosh 1999), the formula of ghosh_calcite."""
    l2 = lam_um * lam_um
    return math.sqrt(1.0 + 0.28604141 + 1.07044083 * l2 / (l2 - 1.00585997e-2) + 1.10202242 * l2 / (l2 - 100.0))


def lowry_quartz_gyration(lam_um):
    """minerals/quartz.txt: the rotatory power along c, rho = K/(L^2 - L0^2) deg/mm (a one-term Drude formula
    fitted to Lowry 1912), as Landau's g33 = lambda rho / pi with rho in rad/um."""
    rho_deg_per_mm = 7.16278575 / (lam_um * lam_um - 0.13239037 ** 2)
    return lam_um * rho_deg_per_mm * DEG * 1e-3 / math.pi


# Indices used by the cases (589.3 nm).
N_O_CALCITE, N_E_CALCITE = 1.6584, 1.4864  # handbook values (Born & Wolf §15.3 table; Hecht ch. 8 table)
LAM_UM = WAVELENGTH_NM / 1000.0
N_O_GHOSH, N_E_GHOSH = ghosh_calcite(LAM_UM)
ARAGONITE = [cauchy(1.51364406, 0.00568, LAM_UM), cauchy(1.66424406, 0.00568, LAM_UM),
             cauchy(1.66864406, 0.00568, LAM_UM)]  # minerals/aragonite.txt, X, Y, Z = n_alpha, n_beta, n_gamma
KTP = list(kato_ktp(LAM_UM))


def binormal_setup(pn, tau, psi):
    """Crystal with binormal 1 at (sin tau, 0, cos tau) and the optic axial plane turned by psi about it:
    R = Ry(tau) Rz(psi) Ry(-Vz), written as ZYZ Euler angles; the air incidence that refracts onto the binormal."""
    vz = biaxial_vz(*pn)
    r_mat = matmul(matmul(rot_y(tau), rot_z(psi)), rot_y(-vz))
    if abs(math.sin(math.acos(max(-1.0, min(1.0, r_mat[2][2]))))) > 1e-6:
        euler = zyz_from_matrix_deg(r_mat)
    else:
        euler = [0.0, math.acos(max(-1.0, min(1.0, r_mat[2][2]))) / DEG, math.atan2(r_mat[1][0], r_mat[0][0]) / DEG]
    r = euler_zyz_deg(*euler)
    err = max(abs(r[i][j] - r_mat[i][j]) for i in range(3) for j in range(3))
    b_check = unit(matvec(r, [math.sin(vz), 0.0, math.cos(vz)]))
    b = [math.sin(tau), 0.0, math.cos(tau)]  # exact: R b_crystal = Ry(tau) Rz(psi) z_hat
    n_vec = scale(pn[1], b)
    xi = n_vec[0]
    return {"euler": euler, "rebuild_error": max(err, norm(sub(b, b_check))), "eta": eta_lab(pn, r), "eps": eps_lab(pn, r),
            "b": b, "N": n_vec, "xi": xi, "k_in": [xi, 0.0, math.sqrt(1.0 - xi * xi)]}


def binormal_modes(setup, phi):
    """Two degenerate waves on the binormal: D_a at angle phi from the in-(x-z)-plane direction, D_b = b x D_a."""
    b, n_vec, eta = setup["b"], setup["N"], setup["eta"]
    d1 = unit(cross([0.0, 1.0, 0.0], b))
    d2 = cross(b, d1)
    da = add(scale(math.cos(phi), d1), scale(math.sin(phi), d2))
    ms = []
    for d in (da, cross(b, da)):
        e = matvec(eta, d)
        ms.append({"D": d, "E": e, "H": cross(n_vec, e), "N": n_vec})
    return ms


def split_study(pn, tau, psi, step_deg=1.0):
    """Largest |R + T_a + T_b - 1| over splits phi (s and p input), and the split angles where it vanishes."""
    setup = binormal_setup(pn, tau, psi)
    worst, best = 0.0, (1.0, None)
    phi = 0.0
    while phi < 180.0 - 1e-9:
        ms = binormal_modes(setup, phi * DEG)
        sols = [solve_explicit(1.0, setup["k_in"], j, ms) for j in ((1.0, 0.0), (0.0, 1.0))]
        e = max(abs(sol["R"] + sum(sol["T_modes"]) - 1.0) for sol in sols)
        worst = max(worst, e)
        if e < best[0]:
            best = (e, phi)
        phi += step_deg
    return worst, best[1], setup



# ----------------------------------------------------------------------------------------------------
# Case construction.

CASES = []
TOL = 1e-12
TOL_DEFECT = 1e-10


def clean(v):
    """Unit vectors for JSON: plain floats; components within 1e-15 of 0 or +-1 (normalisation rounding of an
    exactly axial vector) written as 0.0 or +-1.0."""
    res = []
    for x in v:
        x = float(x)
        if abs(x) < 1e-15:
            x = 0.0
        elif abs(abs(x) - 1.0) < 1e-15:
            x = math.copysign(1.0, x)
        res.append(x)
    return res


def cjson(z):
    return [float(complex(z).real) + 0.0, float(complex(z).imag) + 0.0]


def wave(kind, mode, power, direction=None, n=None, tol=TOL, d_tol=TOL, **extra):
    """One expected wave; tolerances: power and polarization `tol`, direction and n 1e-12, D direction `d_tol`."""
    w = {"kind": kind, "mode": mode}
    if direction is not None:
        w["direction"] = clean(direction)
    if n is not None:
        w["n"] = n
    if power is not None:
        w["power"] = power
    w.update(extra)
    t = {}
    if power is not None:
        t["power"] = tol
    if direction is not None:
        t["direction"] = TOL
    if n is not None:
        t["n"] = TOL
    if "stokes" in extra or "jones_sp" in extra:
        t["polarization"] = tol
    if "D_direction" in extra:
        t["D_direction"] = d_tol
    if "ray_direction" in extra:
        t["ray_direction"] = TOL
    w["tolerance"] = t
    return w


def add_case(name, statement, source, incident, medium1, medium2, waves, sum_tol=TOL, notes=None):
    case = {"name": name, "statement": statement, "source": source, "wavelength_nm": WAVELENGTH_NM,
            "normal": [0.0, 0.0, 1.0], "incident": incident, "medium1": medium1, "medium2": medium2,
            "expected": {"waves": waves, "sum_power": 1.0, "tolerance": {"sum_power": sum_tol}}}
    if notes:
        case["notes"] = notes
    CASES.append(case)
    return case


POLARIZATIONS = {"s": (1.0, 0.0), "p": (0.0, 1.0), "linear45": (math.sqrt(0.5), math.sqrt(0.5)),
                 "circular-right": (math.sqrt(0.5), 1j * math.sqrt(0.5))}
POL_WORDS = {"s": "s-polarized", "p": "p-polarized", "linear45": "linearly polarized at 45 deg (E = (s_hat + p_hat)/sqrt 2)",
             "unpolarized": "unpolarized", "circular-right": "right-circularly polarized (E_s, E_p) = (1, i)/sqrt 2",
             "partial": "partially polarized, Stokes (1, -0.5, 0, 0) (degree of polarization 0.5, p in excess)"}


def pol_json(label):
    if label == "linear45":
        return {"linear_deg": 45}
    if label == "circular-right":
        return {"circular": "right"}
    if label == "partial":
        return {"stokes": [1.0, -0.5, 0.0, 0.0]}
    return label


def isotropic_case(name, n1, n2, theta_deg, pol, statement, source, brewster=False):
    th = theta_deg * DEG
    f = fresnel(n1, n2, th)
    if brewster:  # r_p = 0 exactly at tan(theta) = n2/n1; the formula leaves ~1e-17 of rounding
        f["rp"], f["Rp"] = 0.0, 0.0
    k_in = [math.sin(th), 0.0, math.cos(th)]
    k_r = [math.sin(th), 0.0, -math.cos(th)]
    tir = f["q2"].real == 0.0 and f["q2"].imag > 0.0
    if pol == "unpolarized":
        inputs = [((1.0, 0.0), 0.5), ((0.0, 1.0), 0.5)]
    elif pol == "partial":  # Stokes (1, -0.5, 0, 0): 1/4 of the power s-polarized, 3/4 p, incoherent
        inputs = [((1.0, 0.0), 0.25), ((0.0, 1.0), 0.75)]
    else:
        inputs = [(POLARIZATIONS[pol], 1.0)]
    st_r, st_t = [0.0] * 4, [0.0] * 4
    for (es, ep), wgt in inputs:
        st_r = [st_r[i] + wgt * stokes(f["rs"] * es, f["rp"] * ep)[i] for i in range(4)]
        tf = f["q2"].real / (n1 * math.cos(th))  # Re(n2 cos theta2)/(n1 cos theta1): makes S0 the power
        st_t = [st_t[i] + wgt * tf * stokes(f["ts"] * es, f["tp"] * ep)[i] for i in range(4)]
    if tir:  # |r_s| = |r_p| = 1 exactly: write the power and S0, S1 without the last-bit rounding of |r|^2
        st_r[0] = sum(wgt for _, wgt in inputs)
        st_r[1] = sum(wgt * (abs(es) ** 2 - abs(ep) ** 2) for (es, ep), wgt in inputs)
    r_extra = {"stokes": st_r}
    t_extra = {"stokes": st_t}
    if pol in POLARIZATIONS:
        es, ep = POLARIZATIONS[pol]
        r_extra["jones_sp"] = [cjson(f["rs"] * es), cjson(f["rp"] * ep)]
        if not tir:
            t_extra["jones_sp"] = [cjson(f["ts"] * es), cjson(f["tp"] * ep)]
    waves = [wave("reflected", "s+p", st_r[0], k_r, n1, **r_extra)]
    if tir:
        waves.append(wave("transmitted", "s+p", 0.0, None, None, evanescent=True, q=cjson(f["q2"])))
    else:
        k_t = [f["xi"] / n2, 0.0, f["q2"].real / n2]
        waves.append(wave("transmitted", "s+p", st_t[0], k_t, n2, evanescent=False, **t_extra))
    inc = {"direction": clean(k_in), "polarization": pol_json(pol), "angle_deg": theta_deg}
    return add_case(name, statement, source, inc, {"n": n1}, {"n": n2}, waves), f


# ----------------------------------------------------------------------------------------------------

def main():
    write_dir = None
    if "--write-cases" in sys.argv:
        write_dir = sys.argv[sys.argv.index("--write-cases") + 1]
    if "--markdown" in sys.argv:
        markdown()
        return

    print("petroscope interface verification: analytic reference values (15 significant digits)")
    print("wavelength 589.3 nm; angles in degrees unless marked rad")

    # ---------------------------------------------------------------- [A] Fresnel tables
    print("\n[A] Fresnel coefficients r_s r_p t_s t_p (Born & Wolf §1.5.2 signs), R_s R_p T_s T_p")
    angles = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.9]
    for n1, n2 in ((1.0, 1.5), (1.5, 1.0), (1.0, 2.4)):
        print("  n1 = %g -> n2 = %g" % (n1, n2))
        for a in angles:
            f = fresnel(n1, n2, a * DEG)
            print("   %5.1f  rs %-36s rp %-36s ts %-36s tp %s" % (a, g(f["rs"]), g(f["rp"]), g(f["ts"]), g(f["tp"])))
            print("          Rs %-22s Rp %-22s Ts %-22s Tp %-22s R+T(s)-1 %.3g  R+T(p)-1 %.3g" % (
                g(f["Rs"]), g(f["Rp"]), g(f["Ts"]), g(f["Tp"]), f["Rs"] + f["Ts"] - 1, f["Rp"] + f["Tp"] - 1))

    # ---------------------------------------------------------------- [B] Snell / transmitted angles
    print("\n[B] Snell's law: transmitted angle theta2 = asin(n1 sin theta1 / n2) (deg)")
    for n1, n2, a in ((1.0, 1.5, 30.0), (1.0, 1.5, 60.0), (1.0, 1.5, 89.9), (1.5, 1.0, 30.0), (1.0, 2.4, 45.0),
                      (1.0, 2.4, 80.0)):
        out("n1 %g n2 %g theta1 %g: theta2" % (n1, n2, a), math.asin(n1 * math.sin(a * DEG) / n2) / DEG)

    # ---------------------------------------------------------------- [C] critical angles and TIR
    print("\n[C] Critical angle asin(n2/n1) and total internal reflection (Born & Wolf §1.5.4)")
    out("critical angle 1.5 -> 1 (deg)", math.asin(1.0 / 1.5) / DEG)
    out("critical angle 2.4 -> 1 (deg)", math.asin(1.0 / 2.4) / DEG)
    out("critical angle calcite n_o 1.6584 -> 1 (deg)", math.asin(1.0 / N_O_CALCITE) / DEG)
    nrel = 1.0 / 1.5
    print("  1.5 -> 1: delta = arg(r_s) - arg(r_p); b/a = tan(delta/2) for linear 45 deg input")
    for a in (42.0, 45.0, 50.0, 55.0, 60.0, 70.0, 80.0, 89.0):
        th = a * DEG
        f = fresnel(1.5, 1.0, th)
        d_formula = tir_phase(nrel, th)
        d_direct = cmath.phase(f["rs"]) - cmath.phase(f["rp"])
        out("theta %g: |r_s| |r_p| delta(formula) delta(direct) (deg)" % a, abs(f["rs"]), abs(f["rp"]), d_formula / DEG,
            d_direct / DEG)
        out("          ellipticity b/a = tan(delta/2); S3/S0 = -sin(delta)", math.tan(d_formula / 2), -math.sin(d_formula))
    th_max = math.asin(math.sqrt(2 * nrel ** 2 / (1 + nrel ** 2)))
    out("maximum delta: theta (deg), delta (deg) [tan(dm/2) = (1-n^2)/(2n)]", th_max / DEG, tir_phase(nrel, th_max) / DEG,
        2 * math.atan((1 - nrel ** 2) / (2 * nrel)) / DEG)
    f60 = fresnel(1.5, 1.0, 60 * DEG)
    out("theta 60: r_s, r_p", f60["rs"], f60["rp"])
    out("theta 60: arg r_s, arg r_p (deg)", cmath.phase(f60["rs"]) / DEG, cmath.phase(f60["rp"]) / DEG)
    out("theta 60: q2 = n2 cos theta2 = i sqrt(n1^2 sin^2 - n2^2)", f60["q2"])
    out("theta 60: 1/e penetration depth / wavelength = 1/(2 pi |q2|)", 1.0 / (2 * math.pi * abs(f60["q2"])))
    r45 = stokes(f60["rs"] * math.sqrt(0.5), f60["rp"] * math.sqrt(0.5))
    out("theta 60, linear 45 in: reflected Stokes", *r45)

    # ---------------------------------------------------------------- [D] Brewster
    print("\n[D] Brewster angle tan(theta_B) = n2/n1 (Born & Wolf §1.5.3)")
    for n1, n2 in ((1.0, 1.5), (1.0, 2.4), (1.5, 1.0)):
        tb = math.atan(n2 / n1)
        t2 = math.asin(n1 * math.sin(tb) / n2)
        f = fresnel(n1, n2, tb)
        print("  n1 = %g -> n2 = %g" % (n1, n2))
        out("theta_B, theta2 (deg), theta_B + theta2", tb / DEG, t2 / DEG, (tb + t2) / DEG)
        out("R_s = sin^2(t1-t2)/sin^2(t1+t2), ((n2^2-n1^2)/(n2^2+n1^2))^2", math.sin(tb - t2) ** 2 / math.sin(tb + t2) ** 2,
            ((n2 ** 2 - n1 ** 2) / (n2 ** 2 + n1 ** 2)) ** 2)
        out("Fresnel: R_s, T_s, R_p, T_p", f["Rs"], f["Ts"], f["Rp"], f["Tp"])
        out("r_s, t_s, r_p, t_p", f["rs"], f["ts"], f["rp"], f["tp"])
        k_r = [math.sin(tb), 0.0, -math.cos(tb)]
        k_t = [math.sin(t2), 0.0, math.cos(t2)]
        out("k_r . k_t (reflected perpendicular to refracted)", dot(k_r, k_t))
        out("unpolarized: R = (R_s+R_p)/2, degree of polarization of reflected", (f["Rs"] + f["Rp"]) / 2,
            abs(f["Rs"] - f["Rp"]) / (f["Rs"] + f["Rp"]))
        out("unpolarized: degree of polarization of transmitted", abs(f["Ts"] - f["Tp"]) / (f["Ts"] + f["Tp"]))

    f30 = fresnel(1.0, 1.5, 30 * DEG)
    out("1 -> 1.5 at 30, incident Stokes (1,-0.5,0,0): reflected DoP, transmitted DoP", dop_partial_30(),
        abs(0.25 * f30["Ts"] - 0.75 * f30["Tp"]) / (0.25 * f30["Ts"] + 0.75 * f30["Tp"]))

    # ---------------------------------------------------------------- [E] calcite, normal incidence
    print("\n[E] Calcite (n_o = 1.6584, n_e = 1.4864), optic axis at 45 deg to the face, normal incidence")
    th = 45 * DEG
    ne45 = ne_theta(N_O_CALCITE, N_E_CALCITE, th)
    alpha = walkoff(N_O_CALCITE, N_E_CALCITE, th)
    out("n_e(45) = 1/sqrt(cos^2/n_o^2 + sin^2/n_e^2)", ne45)
    out("walk-off alpha (deg), tan(alpha)", alpha / DEG, math.tan(alpha))
    out("check: tan(alpha) = (n_o^2-n_e^2)/(n_o^2+n_e^2) at 45", (N_O_CALCITE ** 2 - N_E_CALCITE ** 2) / (N_O_CALCITE ** 2 + N_E_CALCITE ** 2))
    out("check: ray angle atan((n_o/n_e)^2 tan 45) - 45 (deg)", math.atan((N_O_CALCITE / N_E_CALCITE) ** 2) / DEG - 45.0)
    for label, n in (("o", N_O_CALCITE), ("e", ne45)):
        out("%s: R = ((n-1)/(n+1))^2, T = 4n/(n+1)^2" % label, ((n - 1) / (n + 1)) ** 2, 4 * n / (n + 1) ** 2)
    out("e ray direction (-sin alpha, 0, cos alpha)", -math.sin(alpha), math.cos(alpha))
    print("  Ghosh 1999 formula (minerals/calcite.txt) at 589.3 nm:")
    ne45g = ne_theta(N_O_GHOSH, N_E_GHOSH, th)
    out("n_o, n_e, n_e(45), walk-off (deg)", N_O_GHOSH, N_E_GHOSH, ne45g, walkoff(N_O_GHOSH, N_E_GHOSH, th) / DEG)

    # ---------------------------------------------------------------- [F] calcite oblique
    print("\n[F] Calcite, 30 deg incidence from air, optic axis in the plane of incidence at 45 deg to the face")
    xi = math.sin(30 * DEG)
    for euler_b in (45.0, -45.0):
        r = euler_zyz_deg(0.0, euler_b, 0.0)
        eta2 = eta_lab([N_O_CALCITE, N_O_CALCITE, N_E_CALCITE], r)
        te, tm = tetm_interface(eta_lab([1.0] * 3, r), eta2, xi)
        n_o_vec = [xi, 0.0, te["q2"].real]
        n_e_vec = [xi, 0.0, tm["q2"].real]
        print("  optic axis (sin %g, 0, cos %g) [euler 0, %g, 0]" % (euler_b, euler_b, euler_b))
        out("o: direction, n, refraction angle (deg), asin(sin30/n_o)", *(unit(n_o_vec) + [norm(n_o_vec),
            math.atan2(xi, te["q2"].real) / DEG, math.asin(xi / N_O_CALCITE) / DEG]))
        out("e: direction, n", *(unit(n_e_vec) + [norm(n_e_vec)]))
        out("e: angle of wave normal to optic axis (deg), n_e(theta) check", math.acos(dot(unit(n_e_vec), [r[0][2], r[1][2], r[2][2]])) / DEG,
            ne_theta(N_O_CALCITE, N_E_CALCITE, math.acos(dot(unit(n_e_vec), [r[0][2], r[1][2], r[2][2]]))))
        out("e: ray direction", *tm_ray(eta2, xi, tm["q2"]))
        out("s (o) in: R_s, T_o; p (e) in: R_p, T_e", te["R"], te["T"], tm["R"], tm["T"])
        eps2 = eps_lab([N_O_CALCITE, N_O_CALCITE, N_E_CALCITE], r)
        e_e = [tm_e(eta2, xi, tm["q2"]), 0.0, eta2[0][2] * tm["q2"] - eta2[2][2] * xi]
        out("Maxwell residuals of the o and e modes", mode_residual(eps2, n_o_vec, [0.0, 1.0, 0.0]), mode_residual(eps2, n_e_vec, e_e))
        # cross-check with the explicit-mode 4x4 solver
        modes, _ = uniaxial_modes(N_O_CALCITE, N_E_CALCITE, [r[0][2], r[1][2], r[2][2]], (xi, 0.0))
        k_in = [xi, 0.0, math.cos(30 * DEG)]
        xs = solve_explicit(1.0, k_in, (1.0, 0.0), modes)
        xp = solve_explicit(1.0, k_in, (0.0, 1.0), modes)
        out("4x4 check: R_s - TE, R_p - TM, T_o - TE, T_e - TM", xs["R"] - te["R"], xp["R"] - tm["R"], xs["T_modes"][0] - te["T"],
            xp["T_modes"][1] - tm["T"])
        # exit face: the same waves leave the slab into air
        te_x, tm_x = tetm_interface(eta2, eta_lab([1.0] * 3, r), xi)
        for label, sol in (("o", te_x), ("e", tm_x)):
            k_out = [xi, 0.0, sol["q2"].real]
            out("exit, %s in: transmitted direction (= incident in air), R, T" % label, *(unit(k_out) + [sol["R"], sol["T"]]))
            if label == "e":
                k_back = [xi, 0.0, sol["q1b"].real]
                out("exit, e in: reflected e direction, n, angle to -z vs incidence angle (deg)", *(unit(k_back) + [norm(k_back),
                    math.atan2(xi, -sol["q1b"].real) / DEG, math.atan2(xi, sol["q1"].real) / DEG]))

    # ---------------------------------------------------------------- [G] biaxial: the defect of §5
    print("\n[G] Biaxial plates near a binormal (paper §5)")
    for label, pn in (("aragonite", ARAGONITE), ("KTP", KTP)):
        vz = biaxial_vz(*pn)
        nb = pn[1]
        print("  %s: n_alpha n_beta n_gamma = %s %s %s" % (label, g(pn[0]), g(pn[1]), g(pn[2])))
        out("Vz (deg), 2V acute (deg)", vz / DEG, 2 * min(vz, math.pi / 2 - vz) / DEG)
        out("binormal in (X,Y,Z): (sin Vz, 0, cos Vz)", math.sin(vz), 0.0, math.cos(vz))
        out("plate cut perpendicular to it: euler (0, -Vz, 0)", -vz / DEG)
        out("normal incidence: R = ((n_beta-1)/(n_beta+1))^2, T = 4 n_beta/(n_beta+1)^2", ((nb - 1) / (nb + 1)) ** 2,
            4 * nb / (nb + 1) ** 2)
        tanchi = math.sqrt((nb ** 2 - pn[0] ** 2) * (pn[2] ** 2 - nb ** 2)) / (pn[0] * pn[2])
        out("internal conical refraction full cone angle chi (deg)", math.atan(tanchi) / DEG)

    # ---------------------------------------------------------------- [I] degenerate split study
    print("\n[H] Exactly on a binormal: power bookkeeping of two degenerate waves (aragonite)")
    print("  binormal tilted tau from the normal, optic plane turned psi about it; an orthonormal split (D_a, D_b = b x D_a)")
    print("  at angle phi; T_a, T_b = each wave's own normal flux. R + T_total = 1 always; R + T_a + T_b = 1 only for one split.")
    for tau_deg in (0.0, 0.5, 1.0, 2.0, 5.0, 10.0):
        for psi_deg in (30.0, 60.0, 90.0):
            worst, phi0, setup = split_study(ARAGONITE, tau_deg * DEG, psi_deg * DEG)
            out("tau %4.1f psi %4.1f: max |R+T_a+T_b-1|, power-conserving phi (deg)" % (tau_deg, psi_deg), worst,
                phi0 if worst > 1e-12 else "any")

    # ---------------------------------------------------------------- cases
    print("\n[I] Case files (power = normal Poynting flux relative to the incident; S0 of 'stokes' = power)")
    build_cases()
    for c in CASES:
        ws = c["expected"]["waves"]
        desc = []
        for w in ws:
            if "power" not in w:
                desc.append("%s %s (power not given)" % (w["kind"][0], w["mode"]))
            elif w["power"] == 0.0 and w.get("evanescent"):
                desc.append("%s %s evanescent" % (w["kind"][0], w["mode"]))
            else:
                desc.append("%s %s %s" % (w["kind"][0], w["mode"], g(w["power"])))
        print("  %-44s %s" % (c["name"], "; ".join(desc)))
        extra = c.get("_print")
        if extra:
            for line in extra:
                print("  %-44s   %s" % ("", line))
    if write_dir:
        os.makedirs(write_dir, exist_ok=True)
        for c in CASES:
            c.pop("_print", None)
            with open(os.path.join(write_dir, c["name"] + ".json"), "w") as fh:
                fh.write(to_json(c) + "\n")
        print("\nwrote %d cases to %s" % (len(CASES), write_dir))


# ----------------------------------------------------------------------------------------------------

def dop_partial_30():
    """Degree of polarization of the wave reflected at 30 deg (1 -> 1.5) for incident Stokes (1, -0.5, 0, 0)."""
    f = fresnel(1.0, 1.5, 30 * DEG)
    i_s, i_p = 0.25 * f["Rs"], 0.75 * f["Rp"]
    return abs(i_s - i_p) / (i_s + i_p)


def build_cases():
    src_31 = "paper §3.1 (Snell's law, total internal reflection); docs/verification.md T1, T5"
    src_32 = "paper §3.2 (Brewster angle, statements 1-3); docs/verification.md T2"
    src_own = "docs/verification.md T5 (Fresnel closed forms)"

    # T1/T5: isotropic 1 -> 1.5
    for a in (0.0, 30.0, 60.0, 89.9):
        for pol in ("s", "p", "unpolarized"):
            isotropic_case("iso-1.0-1.5-%02gdeg-%s" % (a, pol) if a != 89.9 else "iso-1.0-1.5-89.9deg-%s" % pol,
                           1.0, 1.5, a, pol,
                           "Air to glass (n 1 -> 1.5) at %g deg, %s: reflection angle = incidence angle, Snell's law, "
                           "all directions coplanar with the normal, Fresnel powers and amplitudes, R + T = 1." % (a, POL_WORDS[pol]),
                           src_31 + "; " + src_own)
    # 1.5 -> 1
    for pol in ("s", "p", "unpolarized"):
        isotropic_case("iso-1.5-1.0-30deg-%s" % pol, 1.5, 1.0, 30.0, pol,
                       "Glass to air (n 1.5 -> 1) at 30 deg (below the critical angle 41.81 deg), %s: partial reflection, "
                       "Snell's law, Fresnel powers, R + T = 1." % POL_WORDS[pol], src_31 + "; " + src_own)
    c, f = isotropic_case("iso-1.0-1.5-30deg-partial", 1.0, 1.5, 30.0, "partial",
                          "Air to glass (1 -> 1.5) at 30 deg, %s. The reflected wave's degree of polarization is "
                          "%.12g, LOWER than the incident 0.5: reflection and refraction do not always increase the degree "
                          "of polarization (against the paper's §3.2 remark)." % (POL_WORDS["partial"], dop_partial_30()),
                          "paper §3.2 (remark on the degree of polarization); docs/verification.md T2")
    for pol in ("linear45", "unpolarized", "s", "p", "circular-right"):
        c, f = isotropic_case("tir-1.5-1.0-60deg-%s" % pol, 1.5, 1.0, 60.0, pol,
                              "Total internal reflection, glass to air (1.5 -> 1) at 60 deg (critical angle 41.81 deg), %s light: "
                              "R = 1, the transmitted wave is evanescent and carries no power; r_s and r_p differ in phase by "
                              "delta = %.10g deg (Born & Wolf §1.5.4), so linear light at 45 deg leaves elliptical with "
                              "b/a = tan(delta/2) = %.10g; unpolarized light stays unpolarized." % (
                                  POL_WORDS[pol], tir_phase(1 / 1.5, 60 * DEG) / DEG, math.tan(tir_phase(1 / 1.5, 60 * DEG) / 2)),
                              "paper §3.1 (total internal reflection); docs/verification.md T1, T6")
        d = tir_phase(1 / 1.5, 60 * DEG)
        c["expected"]["tir_phase_difference_deg"] = d / DEG
        if pol == "linear45":
            w0 = c["expected"]["waves"][0]
            tol0 = w0.pop("tolerance")
            w0["ellipticity"] = math.tan(d / 2)
            w0["handedness"] = "left"
            tol0["ellipticity"] = TOL
            w0["tolerance"] = tol0
    # 1 -> 2.4
    for a in (45.0, 80.0):
        for pol in ("unpolarized", "linear45"):
            isotropic_case("iso-1.0-2.4-%gdeg-%s" % (a, pol), 1.0, 2.4, a, pol,
                           "Air to a high-index medium (n 1 -> 2.4, diamond-like) at %g deg, %s: Snell's law, Fresnel "
                           "powers and amplitudes (signs of r_s and r_p), R + T = 1." % (a, POL_WORDS[pol]), src_own)

    # T2: Brewster
    tb = math.atan(1.5)
    tb_deg = tb / DEG
    for pol in ("p", "s", "unpolarized"):
        st = {"p": "p-polarized light at the Brewster angle: no reflected wave (R_p = 0), T_p = 1.",
              "s": "s-polarized light at the Brewster angle: BOTH waves exist. R_s = sin^2(t1-t2)/sin^2(t1+t2) = "
                   "((n^2-1)/(n^2+1))^2 = 0.147928994082840 and T_s = 0.852071005917160 (the paper's §3.2 statement 3, "
                   "'no refracted ray', is wrong).",
              "unpolarized": "Unpolarized light at the Brewster angle: the reflected wave is completely s-polarized "
                             "(Stokes S1 = S0), the reflected and refracted wave normals are perpendicular, the refracted "
                             "wave is partially polarized."}[pol]
        c, f = isotropic_case("brewster-%s" % pol, 1.0, 1.5, tb_deg, pol,
                              "Air to glass (1 -> 1.5) at the Brewster angle atan(1.5) = %.12g deg. %s" % (tb_deg, st), src_32,
                              brewster=True)
        c["expected"]["reflected_dot_transmitted"] = 0.0
        c["expected"]["tolerance"]["reflected_dot_transmitted"] = TOL
        c["incident"]["angle_deg"] = tb_deg

    calcite_cases()
    biaxial_cases()
    quartz_cases()


def crystal_wave(kind, mode, power, n_vec, eta, xi, te, tol=TOL, d_tol=TOL):
    """A TE (ordinary / y-polarized) or TM wave in a crystal, with its D and ray directions."""
    n_vec = [xi, 0.0, complex(n_vec[2]).real]
    k = unit(n_vec)
    if te:
        d, ray = [0.0, 1.0, 0.0], k
    else:
        d = unit([n_vec[2], 0.0, -xi])
        ray = tm_ray(eta, xi, complex(n_vec[2]))
    return wave(kind, mode, power, k, norm(n_vec), tol=tol, d_tol=d_tol, stokes=mode_stokes(k, d, power),
                D_direction=clean(d), ray_direction=clean(ray))


def mode_stokes(k_hat, d, power):
    """Stokes vector of a crystal eigenwave, S0 = power: its transverse E (P_k E = D/n^2) is linear along D, so
    S = power (1, cos 2chi, sin 2chi, 0) with chi the angle of D from s_hat toward p_hat of its own k_hat."""
    s_hat, p_hat = sp_basis(k_hat)
    ds, dp = dot(d, s_hat).real, dot(d, p_hat).real
    m = ds * ds + dp * dp
    st = [power, power * (ds * ds - dp * dp) / m, power * 2 * ds * dp / m, 0.0]
    return [0.0 if abs(x) < 1e-17 else x for x in st]


def calcite_cases():
    src = "paper §3.3 (birefringence, statements 1-2); docs/verification.md T3"
    pn = [N_O_CALCITE, N_O_CALCITE, N_E_CALCITE]
    air = eta_lab([1.0] * 3, euler_zyz_deg(0, 0, 0))

    # normal incidence, optic axis at 45 deg to the face in x-z: euler (0, 45, 0) -> Z = (sin 45, 0, cos 45)
    for variant, indices, medium in (("", pn, {"principal_n": pn, "euler_zyz_deg": [0, 45, 0]}),
                                     ("-ghosh", [N_O_GHOSH, N_O_GHOSH, N_E_GHOSH],
                                      {"mineral": "calcite", "euler_zyz_deg": [0, 45, 0]})):
        eta2 = eta_lab(indices, euler_zyz_deg(0, 45, 0))
        te, tm = tetm_interface(air, eta2, 0.0)
        pols = ("unpolarized", "s", "p") if variant == "" else ("unpolarized",)
        for pol in pols:
            ws = {"s": 1.0, "p": 0.0, "unpolarized": 0.5}[pol]
            wp = 1.0 - ws
            r_st = [ws * te["R"] + wp * tm["R"], ws * te["R"] - wp * tm["R"], 0.0, 0.0]
            waves = [wave("reflected", "s+p", r_st[0], [0.0, 0.0, -1.0], 1.0, stokes=r_st),
                     crystal_wave("transmitted", "ordinary", ws * te["T"], [0, 0, te["q2"]], eta2, 0.0, True),
                     crystal_wave("transmitted", "extraordinary", wp * tm["T"], [0, 0, tm["q2"]], eta2, 0.0, False)]
            ne45 = ne_theta(indices[0], indices[2], 45 * DEG)
            stmt = ("Calcite (n_o = %.10g, n_e = %.10g), optic axis at 45 deg to the face in the x-z plane, normal "
                    "incidence from vacuum, %s. Both waves travel along the normal: o with n_o, e with n_e(45) = %.12g; "
                    "the e ray walks off by %.10g deg toward -x (away from the optic axis); o vibrates "
                    "perpendicular to the principal plane (D along y), e in it (D along x); the reflected wave goes "
                    "straight back." % (indices[0], indices[2], POL_WORDS[pol], ne45, walkoff(indices[0], indices[2], 45 * DEG) / DEG))
            c = add_case("calcite-normal-axis45%s-%s" % (variant, pol), stmt, src,
                         {"direction": [0.0, 0.0, 1.0], "polarization": pol}, {"n": 1.0}, medium, waves)
            c["expected"]["walkoff_deg"] = walkoff(indices[0], indices[2], 45 * DEG) / DEG
            if variant:
                c["notes"] = ("medium 2 is petroscope's calcite record; the expected values use the Ghosh (1999) formula of "
                              "minerals/calcite.txt evaluated at 589.3 nm by docs/verification_reference.py: n_o = %r, "
                              "n_e = %r." % (N_O_GHOSH, N_E_GHOSH))

    # oblique incidence, 30 deg, optic axis in the plane of incidence
    xi = math.sin(30 * DEG)
    k_in = [xi, 0.0, math.cos(30 * DEG)]
    for b in (45, -45):
        r = euler_zyz_deg(0, b, 0)
        eta2 = eta_lab(pn, r)
        te, tm = tetm_interface(air, eta2, xi)
        r_st = [0.5 * te["R"] + 0.5 * tm["R"], 0.5 * te["R"] - 0.5 * tm["R"], 0.0, 0.0]
        waves = [wave("reflected", "s+p", r_st[0], [xi, 0.0, -k_in[2]], 1.0, stokes=r_st),
                 crystal_wave("transmitted", "ordinary", 0.5 * te["T"], [0, 0, te["q2"]], eta2, xi, True),
                 crystal_wave("transmitted", "extraordinary", 0.5 * tm["T"], [0, 0, tm["q2"]], eta2, xi, False)]
        stmt = ("Calcite (1.6584, 1.4864), optic axis (sin %d, 0, cos %d) in the plane of incidence, unpolarized light from "
                "vacuum at 30 deg. The o wave obeys Snell's law with n_o (refraction angle asin(0.5/1.6584) = %.12g deg); "
                "the e wave's normal and ray stay in the plane of incidence; with the axis in the plane of incidence the "
                "s part feeds only the o wave and the p part only the e wave." % (b, b, math.asin(xi / N_O_CALCITE) / DEG))
        add_case("calcite-oblique30-axis%+d-unpolarized" % b, stmt, src,
                 {"direction": clean(k_in), "polarization": "unpolarized", "angle_deg": 30.0}, {"n": 1.0},
                 {"principal_n": pn, "euler_zyz_deg": [0, b, 0]}, waves)

    # exit face of a plane-parallel slab (axis +45): each wave of calcite-oblique30-axis+45 leaves into air
    r = euler_zyz_deg(0, 45, 0)
    eta1 = eta_lab(pn, r)
    te, tm = tetm_interface(eta1, air, xi)
    for mode, sol, is_te in (("ordinary", te, True), ("extraordinary", tm, False)):
        n_in = [xi, 0.0, sol["q1"].real]
        n_back = [xi, 0.0, sol["q1b"].real]
        waves = [crystal_wave("reflected", mode, sol["R"], n_back, eta1, xi, is_te),
                 crystal_wave("reflected", "extraordinary" if is_te else "ordinary", 0.0, [0, 0, (tm if is_te else te)["q1b"]],
                              eta1, xi, not is_te),
                 wave("transmitted", "s+p", sol["T"], k_in, 1.0, stokes=[sol["T"], sol["T"] if is_te else -sol["T"], 0.0, 0.0])]
        stmt = ("Exit face of a plane-parallel calcite slab (axis (sin 45, 0, cos 45)): the %s wave refracted at 30 deg by "
                "calcite-oblique30-axis+45 meets the lower face (normal +z, calcite above, vacuum below). The transmitted "
                "wave leaves parallel to the wave incident on the slab, (sin 30, 0, cos 30), %s-polarized; the internally "
                "reflected wave is %s only%s." % (
                    mode, "s" if is_te else "p", mode,
                    "" if is_te else ", and its angle to the normal (%.12g deg) differs from the incidence angle (%.12g deg): "
                    "the law of reflection does not hold inside an anisotropic crystal" % (
                        math.atan2(xi, -sol["q1b"].real) / DEG, math.atan2(xi, sol["q1"].real) / DEG)))
        add_case("calcite-slab-exit-axis+45-%s" % mode, stmt, src + " (statement 2: rays leave parallel to the incident ray)",
                 {"direction": clean(unit(n_in)), "polarization": mode, "angle_deg": math.atan2(xi, sol["q1"].real) / DEG},
                 {"principal_n": pn, "euler_zyz_deg": [0, 45, 0]}, {"n": 1.0}, waves)

    # general azimuth: optic axis at 45 deg to the face, its azimuth 60 deg from the plane of incidence
    axis = [math.sin(45 * DEG) * math.cos(60 * DEG), math.sin(45 * DEG) * math.sin(60 * DEG), math.cos(45 * DEG)]
    modes, eta2 = uniaxial_modes(N_O_CALCITE, N_E_CALCITE, axis, (xi, 0.0))
    eps2 = eps_lab(pn, euler_zyz_deg(60, 45, 0))
    sols = [solve_explicit(1.0, k_in, j, modes) for j in ((1.0, 0.0), (0.0, 1.0))]
    r_un = 0.5 * (sols[0]["R"] + sols[1]["R"])
    # reflected Stokes for unpolarized light: the average of the s-input and p-input Stokes vectors
    st = [0.5 * (stokes(sols[0]["rs"], sols[0]["rp"])[i] + stokes(sols[1]["rs"], sols[1]["rp"])[i]) for i in range(4)]
    waves = [wave("reflected", "s+p", r_un, [xi, 0.0, -k_in[2]], 1.0, stokes=st)]
    for m, name in enumerate(("ordinary", "extraordinary")):
        nv = real3(modes[m]["N"])
        ray = unit(real3(cross(modes[m]["E"], modes[m]["H"])))
        p = 0.5 * (sols[0]["T_modes"][m] + sols[1]["T_modes"][m])
        w = wave("transmitted", name, p, unit(nv), norm(nv), stokes=mode_stokes(unit(nv), real3(modes[m]["D"]), p),
                 D_direction=clean(real3(modes[m]["D"])), ray_direction=clean(ray))
        waves.append(w)
    c = add_case("calcite-oblique30-axis45-azimuth60-unpolarized",
                 "Calcite (1.6584, 1.4864), optic axis at 45 deg to the face and 60 deg in azimuth from the plane of "
                 "incidence, unpolarized light from vacuum at 30 deg. The o wave still obeys Snell's law with n_o "
                 "(refraction angle %.12g deg, in the plane of incidence); the e wave normal stays in the plane of incidence "
                 "(tangential k is conserved) but its ray leaves it; s and p both feed both waves." % (
                     math.asin(xi / N_O_CALCITE) / DEG),
                 src + "; docs/verification.md T3 (general azimuth)",
                 {"direction": clean(k_in), "polarization": "unpolarized", "angle_deg": 30.0}, {"n": 1.0},
                 {"principal_n": pn, "euler_zyz_deg": [60, 45, 0]}, waves)
    c["_print"] = ["mode residuals %s %s; T_total - sum T_modes (s, p in) %s %s" % (
        g(mode_residual(eps2, modes[0]["N"], modes[0]["E"])), g(mode_residual(eps2, modes[1]["N"], modes[1]["E"])),
        g(sols[0]["T_total"] - sum(sols[0]["T_modes"])), g(sols[1]["T_total"] - sum(sols[1]["T_modes"])))]


def biaxial_cases():
    src = "paper §5 (defect near the optic axis of a biaxial plate); docs/verification.md T4"
    air = eta_lab([1.0] * 3, euler_zyz_deg(0, 0, 0))

    def principal(pn, label):
        if label == "aragonite-mineral":
            return {"mineral": "aragonite"}
        return {"principal_n": pn}

    # D1: plate cut perpendicular to a binormal, normal incidence (aragonite, KTP, aragonite by mineral name)
    for label, pn in (("aragonite", ARAGONITE), ("ktp", KTP), ("aragonite-mineral", ARAGONITE)):
        vz = biaxial_vz(*pn)
        nb = pn[1]
        euler = [0.0, -vz / DEG, 0.0]
        medium = principal(pn, label)
        medium["euler_zyz_deg"] = euler
        R = ((nb - 1) / (nb + 1)) ** 2
        r_b = euler_zyz_deg(*euler)
        eta2 = eta_lab(pn, r_b)
        te, tm = tetm_interface(air, eta2, 0.0)
        waves = [wave("reflected", "s+p", R, [0.0, 0.0, -1.0], 1.0, tol=TOL_DEFECT, stokes=[R, 0.0, 0.0, 0.0]),
                 wave("transmitted", "total", 1.0 - R, [0.0, 0.0, 1.0], nb, tol=TOL_DEFECT)]
        name = {"aragonite": "biaxial-binormal-normal-aragonite", "ktp": "biaxial-binormal-normal-ktp",
                "aragonite-mineral": "biaxial-binormal-normal-aragonite-mineral"}[label]
        c = add_case(name,
                     "The paper's defect case (§5): a biaxial plate cut perpendicular to a binormal (%s, n_alpha n_beta n_gamma "
                     "= %.10g %.10g %.10g, Vz = %.12g deg), unpolarized light at normal incidence, so the refracted wave normal "
                     "lies exactly on the binormal (internal conical refraction). The two transmitted eigenwaves are degenerate "
                     "(both n_beta); whatever split a solver reports, reflected + transmitted power must be exactly 1 (the paper "
                     "saw more than 1). Exact values: the central section is a circle, so the plate reflects like an "
                     "isotropic medium of index n_beta: R = ((n_beta-1)/(n_beta+1))^2 for every polarization." % (
                         label.split("-")[0], pn[0], pn[1], pn[2], vz / DEG),
                     src, {"direction": [0.0, 0.0, 1.0], "polarization": "unpolarized"}, {"n": 1.0}, medium, waves,
                     sum_tol=TOL_DEFECT)
        if label == "aragonite-mineral":
            c["notes"] = ("medium 2 is petroscope's aragonite record (Cauchy formulas of minerals/aragonite.txt at 589.3 nm: "
                          "n = %r, %r, %r); the Euler angle puts its binormal on the normal." % tuple(pn))
        c["_print"] = ["TE/TM check: R_s - R, R_p - R: %s %s; Vz %s deg" % (g(te["R"] - R), g(tm["R"] - R), g(vz / DEG))]

    # D2: binormal tilted tau = 2 deg from the normal in the plane of incidence (optic plane = plane of incidence)
    pn = ARAGONITE
    vz = biaxial_vz(*pn)
    nb = pn[1]
    tau = 2.0 * DEG
    theta_air = math.asin(nb * math.sin(tau))
    xi = math.sin(theta_air)
    k_in = [xi, 0.0, math.cos(theta_air)]
    euler = [0.0, (tau - vz) / DEG, 0.0]
    r_b = euler_zyz_deg(*euler)
    eta2 = eta_lab(pn, r_b)
    eps2 = eps_lab(pn, r_b)
    te, tm = tetm_interface(air, eta2, xi)
    b_lab = [math.sin(tau), 0.0, math.cos(tau)]
    r_un = 0.5 * (te["R"] + tm["R"])
    fte = fresnel(1.0, nb, theta_air)  # TE sees n_beta exactly: the isotropic s formulas apply
    waves = [wave("reflected", "s+p", r_un, [xi, 0.0, -k_in[2]], 1.0, tol=TOL_DEFECT,
                  stokes=[r_un, 0.5 * (te["R"] - tm["R"]), 0.0, 0.0]),
             wave("transmitted", "total", 1.0 - r_un, b_lab, nb, tol=TOL_DEFECT)]
    c = add_case("biaxial-binormal-tilted2-aragonite",
                 "Aragonite (%.10g %.10g %.10g) with a binormal tilted 2 deg from the face normal in the plane of incidence "
                 "(the optic axial plane is the plane of incidence), unpolarized light from air at asin(n_beta sin 2 deg) = "
                 "%.12g deg, which refracts exactly onto the binormal (both eigenwaves have index n_beta there). Degenerate "
                 "transmitted waves; R + T = 1. With the optic plane in the plane of incidence, s and p decouple: R_s = %.15g "
                 "(isotropic n_beta), R_p = %.15g (TM closed form)." % (pn[0], pn[1], pn[2], theta_air / DEG, te["R"], tm["R"]),
                 src, {"direction": clean(k_in), "polarization": "unpolarized", "angle_deg": theta_air / DEG}, {"n": 1.0},
                 {"principal_n": pn, "euler_zyz_deg": euler}, waves, sum_tol=TOL_DEFECT)
    c["_print"] = ["R_s %s R_p %s; isotropic n_beta at the same angle: R_s %s R_p %s" % (
        g(te["R"]), g(tm["R"]), g(fte["Rs"]), g(fte["Rp"])),
                   "theta_air %s deg; TE q %s vs n_beta cos tau %s; TM q %s; R_s(TE) - Fresnel(n_beta) %s; "
                   "TM mode residual %s" % (g(theta_air / DEG), g(te["q2"]), g(nb * math.cos(tau)), g(tm["q2"]),
                                            g(te["R"] - fte["Rs"]), g(mode_residual(eps2, [xi, 0.0, tm["q2"]],
                                                                                     [tm_e(eta2, xi, tm["q2"]), 0.0,
                                                                                      eta2[0][2] * tm["q2"] - eta2[2][2] * xi])))]

    # D3: the same binormal, but the optic plane turned by psi = 30 deg about it: s and p couple; exact 4x4 solve
    setup = binormal_setup(pn, tau, 30.0 * DEG)
    euler3, err, b3, n_vec, xi3, k_in3 = (setup[k] for k in ("euler", "rebuild_error", "b", "N", "xi", "k_in"))
    eps3 = setup["eps"]

    def degenerate_modes(phi):
        return binormal_modes(setup, phi)

    base = degenerate_modes(0.0)
    res = max(mode_residual(eps3, n_vec, m["E"]) for m in base)
    pol_results = {}
    for pol, jones in (("s", (1.0, 0.0)), ("p", (0.0, 1.0)), ("linear45", (math.sqrt(0.5), math.sqrt(0.5)))):
        pol_results[pol] = solve_explicit(1.0, k_in3, jones, base)
    # split-dependence of the per-wave powers (the cross-flux of two degenerate waves)
    split_lines = []
    worst = 0.0
    for phi_deg in (0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0, 120.0, 150.0):
        ms = degenerate_modes(phi_deg * DEG)
        for pol, jones in (("s", (1.0, 0.0)), ("p", (0.0, 1.0))):
            sol = solve_explicit(1.0, k_in3, jones, ms)
            excess = sol["R"] + sum(sol["T_modes"]) - 1.0
            worst = max(worst, abs(excess))
            split_lines.append("split phi %5.1f deg, %s in: R + T_a + T_b - 1 = %s (R + T_total - 1 = %s)" % (
                phi_deg, pol, g(excess), g(sol["R"] + sol["T_total"] - 1.0)))
    for pol in ("unpolarized", "linear45"):
        if pol == "unpolarized":
            r_val = 0.5 * (pol_results["s"]["R"] + pol_results["p"]["R"])
            st = [0.5 * (stokes(pol_results[x]["rs"], pol_results[x]["rp"])[i]) for x in ("s", "p") for i in range(4)]
            st = [st[i] + st[4 + i] for i in range(4)]
        else:
            r_val = pol_results[pol]["R"]
            st = stokes(pol_results[pol]["rs"], pol_results[pol]["rp"])
        extra = {"stokes": st}
        if pol == "linear45":
            extra["jones_sp"] = [cjson(pol_results[pol]["rs"]), cjson(pol_results[pol]["rp"])]
        waves = [wave("reflected", "s+p", r_val, [xi3, 0.0, -k_in3[2]], 1.0, tol=TOL_DEFECT, **extra),
                 wave("transmitted", "total", 1.0 - r_val, b3, nb, tol=TOL_DEFECT)]
        c = add_case("biaxial-binormal-tilted2-psi30-aragonite-%s" % pol,
                     "Aragonite with a binormal tilted 2 deg from the face normal (in the plane of incidence) and the optic "
                     "axial plane turned 30 deg about that binormal, %s light from air at %.12g deg refracting exactly onto the "
                     "binormal. s and p couple; the transmitted waves are degenerate (index n_beta), and at oblique incidence an "
                     "arbitrary orthonormal split of them does not conserve the summed power (see docs/verification.md T4): "
                     "reflected + transmitted must be 1." % (POL_WORDS[pol], math.asin(xi3) / DEG),
                     src, {"direction": clean(k_in3), "polarization": pol_json(pol), "angle_deg": math.asin(xi3) / DEG},
                     {"n": 1.0}, {"principal_n": pn, "euler_zyz_deg": euler3}, waves, sum_tol=TOL_DEFECT)
        if pol == "unpolarized":
            c["_print"] = ["euler %s %s %s (rebuild error %s); binormal %s %s %s; mode residual %s; R_s %s R_p %s" % (
                g(euler3[0]), g(euler3[1]), g(euler3[2]), g(err), g(b3[0]), g(b3[1]), g(b3[2]), g(res),
                g(pol_results["s"]["R"]), g(pol_results["p"]["R"]))] + split_lines + [
                "largest |R + T_a + T_b - 1| over the splits above: %s" % g(worst)]

    # D4: near the binormal of the normal-incidence plate: in-plane offsets (decoupled, exact per-mode values)
    euler = [0.0, -vz / DEG, 0.0]
    r_b = euler_zyz_deg(*euler)
    eta2 = eta_lab(pn, r_b)
    for delta in (1e-6, 1e-9):
        xi = math.sin(delta)
        k_in = [xi, 0.0, math.cos(delta)]
        te, tm = tetm_interface(air, eta2, xi)
        n_te = norm([xi, 0.0, te["q2"].real])
        n_tm = norm([xi, 0.0, tm["q2"].real])
        fast_te = n_te < n_tm
        dn = abs(n_te - n_tm)
        d_tol = float("%.1g" % max(TOL, min(1e-2, 1e-14 / dn)))  # eigenvector conditioning ~ eps / (index splitting)
        r_un = 0.5 * (te["R"] + tm["R"])
        waves = [wave("reflected", "s+p", r_un, [xi, 0.0, -k_in[2]], 1.0, tol=TOL_DEFECT,
                      stokes=[r_un, 0.5 * (te["R"] - tm["R"]), 0.0, 0.0]),
                 crystal_wave("transmitted", "fast" if fast_te else "slow", 0.5 * te["T"], [0, 0, te["q2"]], eta2, xi, True,
                              tol=TOL_DEFECT, d_tol=d_tol),
                 crystal_wave("transmitted", "slow" if fast_te else "fast", 0.5 * tm["T"], [0, 0, tm["q2"]], eta2, xi, False,
                              tol=TOL_DEFECT, d_tol=d_tol)]
        for w in waves[1:]:
            w.pop("ray_direction")  # near the binormal the ray direction is itself ill-conditioned
            w["tolerance"].pop("ray_direction")
            w["tolerance"]["polarization"] = max(TOL_DEFECT, 2.0 * d_tol)  # S1, S2 move by 2 x the D azimuth error
        c = add_case("biaxial-near-binormal-%g-rad-aragonite" % delta,
                     "Aragonite plate cut perpendicular to a binormal, unpolarized light from air at %g rad from the normal, "
                     "in the optic axial plane: the refracted wave normal is within ~%g rad of the binormal. The eigenwaves are "
                     "the TE wave (D along y, index n_beta exactly) and the TM wave (index n_beta %+.3g); their powers are "
                     "exact closed forms, and R + T = 1. D-direction tolerance %.3g: near-degenerate eigenvectors are "
                     "ill-conditioned (azimuth error ~ eps / index splitting), powers are not." % (
                         delta, delta, n_tm - n_te, d_tol),
                     src, {"direction": clean(k_in), "polarization": "unpolarized", "angle_rad": delta}, {"n": 1.0},
                     {"principal_n": pn, "euler_zyz_deg": euler}, waves, sum_tol=TOL_DEFECT)
        c["_print"] = ["n_TE %s n_TM %s (n_TM - n_TE %s); R_s %s R_p %s T_s %s T_p %s" % (
            g(n_te), g(n_tm), g(n_tm - n_te), g(te["R"]), g(tm["R"]), g(te["T"]), g(tm["T"]))]

    # D5: near the binormal, offset perpendicular to the optic axial plane (coupled; only the sum is exact)
    delta = 1e-6
    k_in = [0.0, math.sin(delta), math.cos(delta)]
    waves = [wave("reflected", "s+p", None, [0.0, k_in[1], -k_in[2]], 1.0, tol=TOL_DEFECT),
             wave("transmitted", "total", None, tol=TOL_DEFECT)]
    c = add_case("biaxial-near-binormal-perpendicular-1e-06-rad-aragonite",
                 "Aragonite plate cut perpendicular to a binormal, unpolarized light from air at 1e-6 rad from the normal in "
                 "the plane perpendicular to the optic axial plane (y-z): s and p couple and the two transmitted waves are "
                 "nearly degenerate. Only the sum is given: R + T = 1; the reflected wave must go back along the mirror "
                 "direction (a near-binormal solver error shows up here as excess power).",
                 src, {"direction": clean(k_in), "polarization": "unpolarized", "angle_rad": delta}, {"n": 1.0},
                 {"principal_n": pn, "euler_zyz_deg": euler}, waves, sum_tol=TOL_DEFECT)


# ----------------------------------------------------------------------------------------------------
# Optical activity: quartz cut across its optic axis, normal incidence (docs/verification.md T8).
#   Along z, with g = diag(g11, g11, g33): circular E with z x E = +i E (right circular about +z in the
#   (s, p) basis here) has n^2 = n_o^2 - n g33, z x E = -i E has n^2 = n_o^2 + n g33; so n = n_bar -+ g33/2
#   with n_bar = sqrt(n_o^2 + g33^2/4). H = N x E + i kappa E with kappa_xx = kappa_yy = g33/2 is n_bar z x E
#   for both: the two waves have one admittance, and reflection is Fresnel's with n_bar. A wave going back
#   (-z) keeps its lab-frame E, so its sense about its own direction flips: a fast wave reflects into the slow one.

def quartz_cases():
    n_o = ghosh_quartz(LAM_UM)
    src = "Landau & Lifshitz vol. 8 §§100-101; Berreman, JOSA 62, 502 (1972); docs/verification.md T8"
    for hand in ("right", "left"):
        g33 = lowry_quartz_gyration(LAM_UM) * (1.0 if hand == "right" else -1.0)
        n_bar = math.sqrt(n_o * n_o + g33 * g33 / 4)
        r = (1.0 - n_bar) / (1.0 + n_bar)
        big_r = r * r
        half = (1.0 - big_r) / 2
        sense = 1.0 if g33 > 0 else -1.0  # S3 of the fast wave: right circular in a dextrorotatory crystal
        quartz = {"mineral": "quartz", "handedness": hand}
        waves = [wave("reflected", "s+p", big_r, [0.0, 0.0, -1.0], 1.0, stokes=[big_r, big_r, 0.0, 0.0]),
                 wave("transmitted", "fast", half, [0.0, 0.0, 1.0], n_bar - abs(g33) / 2, stokes=[half, 0.0, 0.0, sense * half],
                      ray_direction=[0.0, 0.0, 1.0]),
                 wave("transmitted", "slow", half, [0.0, 0.0, 1.0], n_bar + abs(g33) / 2, stokes=[half, 0.0, 0.0, -sense * half],
                      ray_direction=[0.0, 0.0, 1.0])]
        c = add_case("quartz-axis-normal-%s-s" % hand,
                     "%s-handed quartz (petroscope's record: n_o %.12g by Ghosh 1999, rotatory power %.10g deg/mm along c by the "
                     "Drude fit to Lowry 1912, so g33 = lambda rho/pi = %.10g), optic axis along the normal, s-polarized light from "
                     "vacuum at normal incidence: two circular waves along the normal, indices n_bar -+ |g33|/2 with n_bar = "
                     "sqrt(n_o^2 + g33^2/4); both have the admittance n_bar, so R = ((n_bar - 1)/(n_bar + 1))^2 and each carries "
                     "(1 - R)/2; the fast wave is %s circular (S3 %s 0)." % (
                         hand.capitalize(), n_o, abs(g33) * math.pi / (LAM_UM * DEG * 1e-3), abs(g33), hand, ">" if sense > 0 else "<"),
                     src, {"direction": [0.0, 0.0, 1.0], "polarization": "s"}, {"n": 1.0}, quartz, waves)
        c["_print"] = ["n_o %s g33 %s n_bar %s R %s n_fast %s n_slow %s" % (g(n_o), g(g33), g(n_bar), g(big_r), g(n_bar - abs(g33) / 2), g(n_bar + abs(g33) / 2))]
    g33 = lowry_quartz_gyration(LAM_UM)
    n_bar = math.sqrt(n_o * n_o + g33 * g33 / 4)
    big_r = ((1.0 - n_bar) / (1.0 + n_bar)) ** 2
    waves = [wave("reflected", "fast", 0.0, [0.0, 0.0, -1.0], n_bar - g33 / 2),
             wave("reflected", "slow", big_r, [0.0, 0.0, -1.0], n_bar + g33 / 2, stokes=[big_r, 0.0, 0.0, -big_r],
                  ray_direction=[0.0, 0.0, -1.0]),
             wave("transmitted", "s+p", 1.0 - big_r, [0.0, 0.0, 1.0], 1.0, stokes=[1.0 - big_r, 0.0, 0.0, 1.0 - big_r])]
    add_case("quartz-axis-exit-right-fast",
             "The fast (right circular) wave of right-handed quartz along its optic axis leaving into vacuum at normal "
             "incidence: T = 1 - R with R = ((n_bar - 1)/(n_bar + 1))^2, the transmitted light stays right circular; the "
             "reflected light keeps its field in the lab frame, so about its own direction it turns left circular: it is "
             "the SLOW wave, which carries all of R; the fast reflected wave carries nothing.",
             src, {"direction": [0.0, 0.0, 1.0], "polarization": "fast"}, {"mineral": "quartz", "handedness": "right"},
             {"n": 1.0}, waves)


# ----------------------------------------------------------------------------------------------------
# The tables of docs/verification.md (python3 docs/verification_reference.py --markdown).

def markdown():
    print("<!-- generated by: python3 docs/verification_reference.py --markdown -->")
    for n1, n2 in ((1.0, 1.5), (1.5, 1.0), (1.0, 2.4)):
        print("\n**n1 = %g → n2 = %g**\n" % (n1, n2))
        print("| θ₁ (°) | r_s | r_p | t_s | t_p | R_s | R_p | T_s | T_p |")
        print("|---|---|---|---|---|---|---|---|---|")
        for a in (0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.9):
            f = fresnel(n1, n2, a * DEG)
            print("| %g | %s |" % (a, " | ".join(g(f[k]) for k in ("rs", "rp", "ts", "tp", "Rs", "Rp", "Ts", "Tp"))))
    print("\n**TIR, n1 = 1.5 → n2 = 1 (critical angle %s°)**\n" % g(math.asin(1 / 1.5) / DEG))
    print("| θ₁ (°) | arg r_s (°) | arg r_p (°) | δ = arg r_s − arg r_p (°) | B&W formula δ (°) | b/a = tan(δ/2) | S3/S0 (45° input) |")
    print("|---|---|---|---|---|---|---|")
    for a in (42.0, 45.0, 50.0, 51.6711818985441, 55.0, 60.0, 70.0, 80.0, 89.0):
        f = fresnel(1.5, 1.0, a * DEG)
        d = tir_phase(1 / 1.5, a * DEG)
        print("| %s | %s | %s | %s | %s | %s | %s |" % (g(a), g(cmath.phase(f["rs"]) / DEG), g(cmath.phase(f["rp"]) / DEG),
              g((cmath.phase(f["rs"]) - cmath.phase(f["rp"])) / DEG), g(d / DEG), g(math.tan(d / 2)), g(-math.sin(d))))
    print("\n**Degenerate split on a binormal (aragonite): largest |R + T_a + T_b − 1| over splits φ (s and p input)**\n")
    print("| tilt τ of the binormal from the normal (°) | ψ = 30° | ψ = 60° | ψ = 90° |")
    print("|---|---|---|---|")
    for tau_deg in (0.0, 0.5, 1.0, 2.0, 5.0, 10.0):
        row = []
        for psi_deg in (30.0, 60.0, 90.0):
            worst, phi0, _ = split_study(ARAGONITE, tau_deg * DEG, psi_deg * DEG)
            row.append("%s (φ₀ %s)" % (g(worst), "any" if worst < 1e-12 else "= %s°" % g(phi0)))
        print("| %g | %s |" % (tau_deg, " | ".join(row)))
    build_cases()
    print("\n**Case index**\n")
    print("| case | incident | expected waves: kind mode power [n] | tolerance (power, sum) |")
    print("|---|---|---|---|")
    for c in CASES:
        inc = c["incident"]
        pol = inc["polarization"]
        pol = pol if isinstance(pol, str) else ", ".join("%s %s" % kv for kv in pol.items())
        ang = inc.get("angle_deg", inc.get("angle_rad"))
        ang_s = ("%s°" % g(ang)) if "angle_deg" in inc else ("%s rad" % g(ang)) if ang is not None else "0°"
        ws = []
        for w in c["expected"]["waves"]:
            if w.get("evanescent"):
                ws.append("%s %s evanescent, 0" % (w["kind"][0], w["mode"]))
            elif "power" in w:
                ws.append("%s %s %s%s" % (w["kind"][0], w["mode"], g(w["power"]), (" [n %s]" % g(w["n"])) if "n" in w and w["kind"] == "transmitted" else ""))
            else:
                ws.append("%s %s (power free)" % (w["kind"][0], w["mode"]))
        tol = min(w["tolerance"].get("power", 1.0) for w in c["expected"]["waves"])
        print("| `%s` | %s, %s | %s | %s, %s |" % (c["name"], ang_s, pol, "; ".join(ws), g(tol) if tol < 1 else "–",
                                               g(c["expected"]["tolerance"]["sum_power"])))


# ----------------------------------------------------------------------------------------------------
# JSON writer: objects one key per line, arrays of numbers on one line.

def scalar_json(x):
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return json.dumps(x, ensure_ascii=False)
    if isinstance(x, float):
        return "0.0" if x == 0.0 else repr(x)
    return repr(x)


def is_flat(obj):
    if isinstance(obj, list):
        return all(not isinstance(x, (dict, list)) or (isinstance(x, list) and is_flat(x)) for x in obj)
    return not isinstance(obj, dict)


def to_json(obj, indent=0):
    pad = "  " * indent
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        if all(is_flat(v) for v in obj.values()):
            one = "{" + ", ".join("%s: %s" % (json.dumps(k), to_json(v)) for k, v in obj.items()) + "}"
            if len(one) <= 100:
                return one
        items = ['%s  %s: %s' % (pad, json.dumps(k), to_json(v, indent + 1)) for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(obj, list):
        if is_flat(obj):
            return "[" + ", ".join(to_json(x) for x in obj) + "]"
        items = ["%s  %s" % (pad, to_json(x, indent + 1)) for x in obj]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return scalar_json(obj)


if __name__ == "__main__":
    main()
