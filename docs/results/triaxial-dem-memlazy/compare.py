# Triaxial bounds against a stored run: peak friction angle, dilatancy angle (from SUMMARY.md),
# axial and lateral stress at the peak of q/p and the mean wall stress p at the end (CSVs).
import csv, re, sys
new, old = sys.argv[1], sys.argv[2]
def summ(d):
    t = open(d + '/SUMMARY.md').read()
    g = lambda k: [float(x) for x in re.search(r'\| ' + re.escape(k) + r' \| ([-\d.]+) \| ([-\d.]+) \|', t).groups()]
    return g('peak friction angle [deg]'), g('dilatancy angle [deg]')
def rows(d, law):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(f'{d}/triaxial_{law}.csv'))]
(pn, dn), (po, do) = summ(new), summ(old)
print(f"peak friction angle [deg]: {pn} vs {po}: {pn[0]-po[0]:+.2f} / {pn[1]-po[1]:+.2f} (0.5)")
print(f"dilatancy angle [deg]: {dn} vs {do}: {dn[0]-do[0]:+.2f} / {dn[1]-do[1]:+.2f} (0.5)")
for key, label in [('sigma_axial', 'axial stress at the peak'), ('sigma_lateral', 'lateral stress at the peak')]:
    out = []
    for law in ['coulomb', 'creep']:
        a, b = rows(new, law), rows(old, law)
        pa = max(a, key=lambda r: r['q_over_p']); pb = max(b, key=lambda r: r['q_over_p'])
        out.append(100 * (pa[key] / pb[key] - 1))
    print(f"{label}: {out[0]:+.2f} % / {out[1]:+.2f} % (1 %)")
out = []
for law in ['coulomb', 'creep']:
    a, b = rows(new, law), rows(old, law)
    out.append(100 * (a[-1]['p'] / b[-1]['p'] - 1))
print(f"mean wall stress at 20 % strain: {out[0]:+.2f} % / {out[1]:+.2f} % (1 %)")
