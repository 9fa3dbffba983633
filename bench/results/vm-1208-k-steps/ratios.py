# Ratios A / B of ns per particle-step within each round (paired.log: 6 rounds of 5 runs).
import statistics as st, sys
rows = [l.split() for l in open(sys.argv[1] if len(sys.argv) > 1 else 'paired.log')]
per_round = int(sys.argv[2]) if len(sys.argv) > 2 else 5
rounds = [rows[i:i + per_round] for i in range(0, len(rows), per_round)]
res = {}
for r in rounds:
    a = {x[1]: float(x[5]) for x in r if x[0] == 'A'}
    for x in r:
        if x[0] != 'A':
            res.setdefault((x[0], x[1]), []).append(a[x[1]] / float(x[5]))
for k, v in sorted(res.items()):
    print(*k, ' '.join(f'{y:.2f}' for y in v), 'median %.2f' % st.median(v))
for lab, t in sorted({(x[0], x[1]) for x in rows}):
    v = [float(x[5]) for x in rows if x[0] == lab and x[1] == t]
    print(lab, t, 'ns per particle-step min %.1f median %.1f max %.1f' % (min(v), st.median(v), max(v)))
print('state hashes:', sorted({x[10] for x in rows}))
