# Usage: python3 crates/law/benches/mindlin_lazy_potential.py TRACE (a CREEP_MINDLIN_TRACE file).
# Lead (b) of issue 15 on the DEM trace: how many stored pieces a per-piece margin test could
# skip. A piece is skippable when its margin to the slip limit before the update,
# m = min over the piece of (kappa s - |u|), exceeds the bound of its shrinkage in one update,
# |du| + (|beta| + kappa) |da2|. Also counts pieces that are in fact stuck (trial within the
# limit at both ends, the piece's outer end being where it slips first).
import struct, math
b = open(__import__('sys').argv[1], 'rb').read()
v = struct.unpack('<%dd' % (len(b) // 8), b)
recs = [v[i * 59:(i + 1) * 59] for i in range(len(v) // 59)]
tot = skip = stuck = 0
for r in recs:
    rs, es, gs, g, nu, mu, c11, a, dux, duy = r[:10]
    st = r[10:]
    a0, n = st[0], int(st[1])
    kappa = mu * es / (4 * gs * rs)
    if not (0 < kappa < math.inf) or a == 0:
        continue
    da2 = a * a - a0 * a0
    du = math.hypot(dux, duy)
    x_lo = 0.0
    for i in range(n):
        x_hi, bx, by, cx, cy = st[4 + 5 * i:9 + 5 * i]
        if x_hi > a:  # leaving springs: touched anyway
            tot += 1
            x_lo = x_hi
            continue
        # margin before: sample the piece densely (the margin is smallest at the outer end for
        # pieces at the limit, but sample anyway)
        m = math.inf
        for k in range(21):
            x = x_lo + (x_hi - x_lo) * k / 20
            s = a0 * a0 - x * x
            m = min(m, kappa * s - math.hypot(bx * s + cx, by * s + cy))
        bound = du + (math.hypot(bx, by) + kappa) * abs(da2)
        tot += 1
        if m > bound:
            skip += 1
        # after the update: stuck?
        ok = True
        for k in range(21):
            x = x_lo + (x_hi - x_lo) * k / 20
            s = a * a - x * x
            ux, uy = bx * s + cx - bx * da2 + dux, by * s + cy - by * da2 + duy
            # u_new = beta s_new + c + du - beta da2
            if math.hypot(ux, uy) > kappa * s * (1 + 1e-12):
                ok = False
        stuck += ok
        x_lo = x_hi
print(f"{len(recs)} updates, {tot} stored pieces ({tot/len(recs):.2f} per update): "
      f"stuck after the update {stuck} ({stuck/tot:.1%}), skippable by the margin bound {skip} "
      f"({skip/tot:.1%}, {skip/len(recs):.2f} per update)")
