#!/usr/bin/env python3
"""Compares motion tables (CSV) of two runs: same header, same rows, every value
equal to `tol` relative to its column's largest magnitude. Used to show that a
refactoring left the bundled mechanisms' tables unchanged.

Usage: compare_tables.py DIR_A DIR_B [--tol 1e-12]
Prints one line per table and exits 1 on any difference."""
import argparse, csv, math, os, sys


def read(path):
    with open(path) as f:
        lines = f.read().splitlines()
    note = lines[0] if lines and lines[0].startswith('#') else None
    body = lines[1:] if note else lines
    rows = list(csv.reader(body))
    return note, rows[0], [[float(x) for x in r] for r in rows[1:]]


def compare(a, b, tol):
    na, ha, ra = read(a)
    nb, hb, rb = read(b)
    if ha != hb: return 'headers differ'
    if (na is None) != (nb is None): return 'partial marks differ: %r vs %r' % (na, nb)
    if len(ra) != len(rb): return 'row counts differ: %d vs %d' % (len(ra), len(rb))
    worst = 0.0
    for c in range(len(ha)):
        scale = max([abs(r[c]) for r in ra if math.isfinite(r[c])] + [1e-300])
        for x, y in zip((r[c] for r in ra), (r[c] for r in rb)):
            if math.isnan(x) and math.isnan(y): continue
            worst = max(worst, abs(x - y) / scale)
    return None if worst <= tol else 'largest relative difference %.3g' % worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('a'); ap.add_argument('b'); ap.add_argument('--tol', type=float, default=1e-12)
    args = ap.parse_args()
    bad = 0
    for name in sorted(os.listdir(args.a)):
        if not name.endswith('.csv'): continue
        other = os.path.join(args.b, name)
        why = 'missing' if not os.path.exists(other) else compare(os.path.join(args.a, name), other, args.tol)
        print('%-45s %s' % (name, why or 'same'))
        bad += why is not None
    print('%d tables differ' % bad)
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
