#!/usr/bin/python3
"""A branch of the N-link chain followed in arbitrary precision (mpmath): the independent
reference for src/nlink_path.c where a branch turns sharply (tests/unit/steady/test_nlink_path.c,
test_corners). From the birth omega_k of mode k to the first crossing of FACTOR omega_k, g = 1.

Equations (the force balance of src/nlink_balance.c, written out again here):
  V_i = g sum_{j>=i} m_j,  H_i = V_i tan th_i (H_{N+1} = 0),
  rho_i = (H_i - H_{i+1}) / (m_i w^2),   rho_0 = 0,
  R_i = rho_i - rho_{i-1} - l_i sin th_i = 0,  i = 1..N.
Unknowns x = (w, th_1..th_N). Jacobian: dense (N x (N+1)) from the exact derivatives
  drho_i/dth_i = V_i sec^2 th_i / (m_i w^2), drho_i/dth_{i+1} = -V_{i+1} sec^2 th_{i+1} / (m_i w^2),
  dR_i/dw = -2 (rho_i - rho_{i-1}) / w.
Pseudo-arclength continuation (Keller 1977; Allgower & Georg 1990, ch. 2) in the metric
ds^2 = (dw/w)^2 + (1/N) sum dth^2 (the library's), predictor x0 + ds t0, Newton corrector on
{R = 0, (M0 t0).(x - x0) = ds}, dense LU in mpmath. A trial step is accepted only if
  * Newton converges (componentwise relative correction < 10^-(dps-15)) in <= NEWT iterations,
  * the corrected point is within TURN*ds of the predictor (metric),
  * the tangent turns by at most TURN (metric angle),
  * the orientation sign det[J; t^T] (t along the travel) is unchanged (it flips only at a
    branch point, or where the corrector lands on the neighbouring curve of an unfolded one),
  * the Sturm index of the force-balance Jacobian A = dR/dth (number of negative eigenvalues;
    A is tridiagonal with positive products of its off-diagonal pairs, so it is similar to a
    symmetric one) changes by exactly the number of folds of the step (sign changes of t_w,
    0 or 1),
  * no link angle changes by more than DTHMAX;
otherwise ds is halved (below 10^-(dps-12) the run stops and says so on a "# FAIL" line). ds
grows 1.5-fold after an easy step, up to DSMAX.
Start: the k-th eigenpair of the linearisation at the hanging chain (K th = w^2 diag(l) th),
a point at amplitude EPS along the eigenvector polished by Newton's method, heading into
increasing amplitude.

Usage: branch_mp.py --length l_1,..,l_N --mass m_1,..,m_N MODE [--dps 50] [--dsmax 0.005]
           [--turn 0.02] [--dthmax 0.02] [--factor 10] [--maxsteps K] [--out FILE]
Output: "P step w th_1..th_N index orientation ds turn" per accepted point (25 digits), then
"CROSS w th_1..th_N" at FACTOR omega_k (the link angles test_corners compares with, up to the
mirror image) and a "# steps ..." summary with the smallest step and the sharpest turn. A chain
of 12 links takes 0.5 to 3 minutes at 50 digits.
"""
import sys, argparse, time
import mpmath as mp


def parse_list(text):
    """comma-separated values, each rounded to double first: the chain the library sees"""
    return [mp.mpf(float(v)) for v in text.split(',')]


class Chain:
    def __init__(self, L, M):
        self.L, self.M, self.n = L, M, len(L)
        V = [mp.mpf(0)] * self.n
        acc = mp.mpf(0)
        for i in range(self.n - 1, -1, -1):
            acc += M[i]
            V[i] = acc
        self.V = V

    def resid(self, x, jac=False):
        n, L, M, V = self.n, self.L, self.M, self.V
        w = x[0]
        th = x[1:]
        w2 = w * w
        s = [mp.sin(t) for t in th]
        c = [mp.cos(t) for t in th]
        H = [V[i] * s[i] / c[i] for i in range(n)] + [mp.mpf(0)]
        rho = [(H[i] - H[i + 1]) / (M[i] * w2) for i in range(n)]
        R = []
        for i in range(n):
            ra = rho[i - 1] if i > 0 else mp.mpf(0)
            R.append(rho[i] - ra - L[i] * s[i])
        if not jac:
            return R
        J = mp.zeros(n, n + 1)
        dH = [V[i] / (c[i] * c[i]) for i in range(n)]  # dH_i/dth_i
        # drho_i/dth_j: j = i: dH_i/(m_i w2); j = i+1: -dH_{i+1}/(m_i w2)
        for i in range(n):
            ra = rho[i - 1] if i > 0 else mp.mpf(0)
            J[i, 0] = -2 * (rho[i] - ra) / w
            # rho_i terms
            J[i, 1 + i] += dH[i] / (M[i] * w2)
            if i + 1 < n:
                J[i, 2 + i] += -dH[i + 1] / (M[i] * w2)
            # -rho_{i-1} terms
            if i > 0:
                J[i, i] += -dH[i - 1] / (M[i - 1] * w2)
                J[i, 1 + i] += dH[i] / (M[i - 1] * w2)
            J[i, 1 + i] += -L[i] * c[i]
        return R, J

    def index(self, J):
        """negative eigenvalues of A = J[:, 1:] (Sturm count of its symmetric equivalent)."""
        n = self.n
        neg = 0
        d = None
        for i in range(n):
            a = J[i, 1 + i]
            if i > 0:
                p = J[i, i] * J[i - 1, 1 + i]  # A[i,i-1] * A[i-1,i]
                a = a - p / d
            if a < 0:
                neg += 1
            d = a
        return neg


def metric(x, n):
    return [1 / (x[0] * x[0])] + [mp.mpf(1) / n] * n


def mdot(a, b, g):
    return mp.fsum(a[i] * b[i] * g[i] for i in range(len(a)))


def bordered(n, J, row):
    """[J; row]: the N x (N+1) Jacobian with the row below it"""
    B = mp.zeros(n + 1, n + 1)
    for i in range(n):
        for j in range(n + 1):
            B[i, j] = J[i, j]
    for j in range(n + 1):
        B[n, j] = row[j]
    return B


def tangent(ch, x, row):
    """t with J t = 0, row . t = 1 (unnormalised), and J at x."""
    n = ch.n
    R, J = ch.resid(x, jac=True)
    t = mp.lu_solve(bordered(n, J, row), mp.matrix([0] * n + [1]))
    return [t[i] for i in range(n + 1)], J


def orient_det(ch, J, t):
    """the sign of det [J; t]"""
    return 1 if mp.det(bordered(ch.n, J, t)) > 0 else -1


def newton(ch, x, row, rhs_val, x0, tol, itmax):
    """Newton on R(x) = 0, row . (x - x0) = rhs_val. Returns (x, iterations, ok)."""
    n = ch.n
    x = list(x)
    for it in range(1, itmax + 1):
        R, J = ch.resid(x, jac=True)
        B = bordered(n, J, row)
        f = mp.matrix(n + 1, 1)
        for i in range(n):
            f[i] = -R[i]
        f[n] = -(mp.fsum(row[j] * (x[j] - x0[j]) for j in range(n + 1)) - rhs_val)
        try:
            dx = mp.lu_solve(B, f)
        except ZeroDivisionError:
            return x, it, False
        rel = mp.mpf(0)
        for j in range(n + 1):
            x[j] += dx[j]
            rel = max(rel, abs(dx[j]) / (abs(x[j]) + mp.mpf(10) ** (-300)))
        if not all(abs(v) < mp.pi / 2 for v in x[1:]):
            return x, it, False
        if rel < tol:
            return x, it, True
    return x, itmax, False


def birth(ch, k):
    n = ch.n
    # linearisation: A0(w) = K / w^2 - diag(l); K th = w^2 diag(l) th
    x = [mp.mpf(1)] + [mp.mpf(0)] * n
    R, J = ch.resid(x, jac=True)  # at w = 1, th = 0: J[:,1:] = K - diag(l)
    K = mp.zeros(n, n)
    for i in range(n):
        for j in range(n):
            K[i, j] = J[i, 1 + j] + (ch.L[i] if i == j else 0)
        for j in range(n):
            K[i, j] /= ch.L[i]
    E, EV = mp.eig(K)
    order = sorted(range(n), key=lambda i: mp.re(E[i]))
    lam = mp.re(E[order[k - 1]])
    v = [mp.re(EV[i, order[k - 1]]) for i in range(n)]
    big = max(v, key=lambda a: abs(a))
    v = [a / big for a in v]  # max |v| = 1, positive at its largest
    return mp.sqrt(lam), v, [mp.sqrt(mp.re(E[o])) for o in order]


def run(args):
    mp.mp.dps = args.dps
    L, M = parse_list(args.length), parse_list(args.mass)
    if len(L) != len(M) or not L or min(L + M) <= 0:
        sys.exit('branch_mp.py: --length and --mass need the same number (N >= 1) of positive '
                 'values')
    ch = Chain(L, M)
    if not 1 <= args.mode <= ch.n:
        sys.exit('branch_mp.py: mode %d: the chain of %d links has modes 1..%d'
                 % (args.mode, ch.n, ch.n))
    n, k = ch.n, args.mode
    wk, v, allw = birth(ch, k)
    tol = mp.mpf(10) ** (-(args.dps - 15))
    eps = mp.mpf(args.eps)
    # start point: amplitude along v fixed (v . th = eps v.v)
    row = [mp.mpf(0)] + v
    x0 = [wk] + [mp.mpf(0)] * n
    xs = [wk] + [eps * a for a in v]
    vv = mp.fsum(a * a for a in v)
    x, it, ok = newton(ch, xs, row, eps * vv, x0, tol, 30)
    if not ok:
        sys.exit('branch_mp.py: the first point of mode %d did not converge' % k)
    t, J = tangent(ch, x, row)
    g = metric(x, n)
    nt = mp.sqrt(mdot(t, t, g))
    t = [a / nt for a in t]
    osign = orient_det(ch, J, t)
    idx = ch.index(J)
    target = args.factor * wk
    out = open(args.out, 'w') if args.out else sys.stdout
    out.write('# birth %s  mode %d  n %d  dps %d dsmax %g turn %g\n'
              % (mp.nstr(wk, 20), k, n, args.dps, args.dsmax, args.turn))
    out.write('# all births ' + ' '.join(mp.nstr(a, 17) for a in allw) + '\n')

    def emit(tag, x, extra=''):
        out.write(tag + ' ' + ' '.join(mp.nstr(a, 25) for a in x) + extra + '\n')

    emit('P 0', x, ' %d %d' % (idx, osign))
    ds = mp.mpf(args.dsmax) / 10
    DS_MIN = mp.mpf(10) ** (-(args.dps - 12))
    s_arc = mp.mpf(0)
    steps = rej = folds = 0
    minds = ds
    maxcurv = mp.mpf(0)
    maxcurv_at = None
    t_start = time.time()
    while True:
        g0 = metric(x, n)
        row = [t[i] * g0[i] for i in range(n + 1)]
        while True:
            if ds < DS_MIN:
                out.write('# FAIL ds below %s at w=%s\n' % (mp.nstr(DS_MIN, 3), mp.nstr(x[0], 20)))
                out.close()
                return 1
            pred = [x[i] + ds * t[i] for i in range(n + 1)]
            x1, its, ok = newton(ch, pred, row, ds, x, tol, args.newt)
            why = None
            if not ok:
                why = 'newton'
            else:
                g1 = metric(x1, n)
                d = [x1[i] - pred[i] for i in range(n + 1)]
                if mp.sqrt(mdot(d, d, g1)) > args.turn * ds:
                    why = 'predictor'
                elif max(abs(x1[i] - x[i]) for i in range(1, n + 1)) > args.dthmax:
                    why = 'dtheta'
                else:
                    t1, J1 = tangent(ch, x1, row)
                    nt = mp.sqrt(mdot(t1, t1, g1))
                    t1 = [a / nt for a in t1]
                    cs = mdot(t1, t, g1) / mp.sqrt(mdot(t, t, g1))
                    ang = mp.acos(max(-1, min(1, cs)))
                    if ang > args.turn:
                        why = 'turn'
                    else:
                        os1 = orient_det(ch, J1, t1)
                        idx1 = ch.index(J1)
                        fold = 1 if (t1[0] > 0) != (t[0] > 0) else 0
                        if os1 != osign:
                            why = 'orientation'
                        elif abs(idx1 - idx) != fold:
                            why = 'index'
            if why is None:
                break
            rej += 1
            ds /= 2
            minds = min(minds, ds)
        # accepted
        steps += 1
        folds += fold
        curv = ang / ds
        if curv > maxcurv:
            maxcurv, maxcurv_at = curv, x1[0]
        xprev, x, t, idx = x, x1, t1, idx1
        s_arc += ds
        emit('P %d' % steps, x, ' %d %d %s %s' % (idx, osign, mp.nstr(ds, 3), mp.nstr(ang, 3)))
        if steps % 200 == 0:
            out.flush()
        # first crossing of the target rate
        if (xprev[0] - target) * (x[0] - target) <= 0:
            lam = (target - xprev[0]) / (x[0] - xprev[0])
            xi = [xprev[i] + lam * (x[i] - xprev[i]) for i in range(n + 1)]
            rowc = [mp.mpf(1)] + [mp.mpf(0)] * n
            xc, its, ok = newton(ch, xi, rowc, target - xi[0], xi, tol, 40)
            dd = [xc[i] - xi[i] for i in range(n + 1)]
            far = mp.sqrt(mdot(dd, dd, metric(xc, n)))
            emit('CROSS', xc, ' ok=%s dist_from_interp=%s' % (ok, mp.nstr(far, 3)))
            break
        if args.maxsteps and steps >= args.maxsteps:
            out.write('# stopped at maxsteps\n')
            break
        easy = its <= 4 and ang < args.turn / 3
        if easy:
            ds = min(ds * mp.mpf(1.5), mp.mpf(args.dsmax))
    out.write('# steps %d rejected %d folds %d arclength %s min ds %s max turn/ds %s at w=%s '
              'time %.0fs\n'
              % (steps, rej, folds, mp.nstr(s_arc, 8), mp.nstr(minds, 3), mp.nstr(maxcurv, 3),
                 mp.nstr(maxcurv_at, 12), time.time() - t_start))
    out.close()
    return 0


if __name__ == '__main__':
    ap = argparse.ArgumentParser(description='a branch of the N-link chain in mpmath')
    ap.add_argument('--length', required=True, help='link lengths l_1..l_N, comma-separated')
    ap.add_argument('--mass', required=True, help='masses m_1..m_N, comma-separated')
    ap.add_argument('mode', type=int)
    ap.add_argument('--dps', type=int, default=50)
    ap.add_argument('--dsmax', type=float, default=0.005)
    ap.add_argument('--turn', type=float, default=0.02)
    ap.add_argument('--dthmax', type=float, default=0.02)
    ap.add_argument('--newt', type=int, default=8)
    ap.add_argument('--factor', type=float, default=10)
    ap.add_argument('--eps', type=str, default='1e-12')
    ap.add_argument('--maxsteps', type=int, default=0)
    ap.add_argument('--out')
    sys.exit(run(ap.parse_args()))
