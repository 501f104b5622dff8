# Usage: python3 crates/law/benches/mindlin_limit_angles.py TRACE (a CREEP_MINDLIN_TRACE file).
# Issue 15, branch coalesce: the angles between neighbouring annuli at the slip limit (c = 0,
# |beta| = kappa to 1e-9, as creep_law::mindlin's `at_limit`) in the trace's stored states, i.e.
# what eager coalescing within an angle theta_tol could join. Records: 59 little-endian f64,
# r_star, e_star, g_star, g, nu, mu, c11, a, du.x, du.y and the state's to_array
# (a, n, q.x, q.y, then per piece x_hi, beta.x, beta.y, c.x, c.y).
# (The angles an update leaves before its capacity merge, and what each theta_tol does to a
# packing, need the engine: see docs/results/triaxial-default/README.md.)
import math
import struct
import sys

b = open(sys.argv[1], 'rb').read()
v = struct.unpack('<%dd' % (len(b) // 8), b)
recs = [v[i * 59:(i + 1) * 59] for i in range(len(v) // 59)]
angs = []
n_lim = n_pieces = 0
for r in recs:
    rs, es, gs, g, nu, mu, c11, a, dux, duy = r[:10]
    st = r[10:]
    n = int(st[1])
    kappa = mu * es / (4 * gs * rs)
    pcs = [st[4 + 5 * i:9 + 5 * i] for i in range(n)]
    n_pieces += n
    lim = [p[3] == 0 and p[4] == 0 and math.hypot(p[1], p[2]) >= kappa * (1 - 1e-9) for p in pcs]
    n_lim += sum(lim)
    for i in range(n - 1):
        if lim[i] and lim[i + 1]:
            b1, b2 = pcs[i][1:3], pcs[i + 1][1:3]
            c = (b1[0] * b2[0] + b1[1] * b2[1]) / (math.hypot(*b1) * math.hypot(*b2))
            angs.append(math.acos(max(-1.0, min(1.0, c))))
print(f"{len(recs)} records: {n_pieces / len(recs):.2f} pieces, {n_lim / len(recs):.2f} at the "
      f"limit, {len(angs) / len(recs):.2f} neighbouring pairs at the limit per record")
angs.sort()
for t in [1e-6, 1e-4, 1e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0]:
    k = sum(1 for x in angs if x <= t)
    print(f"angle <= {t:g} rad: {k} pairs ({k / max(len(angs), 1):.1%})")
if angs:
    q = lambda f: angs[int(f * (len(angs) - 1))]
    print("quantiles 10/25/50/75/90 %: " + ", ".join(f"{q(f):.3g}" for f in (0.1, 0.25, 0.5, 0.75, 0.9)) + " rad")
