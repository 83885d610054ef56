#!/usr/bin/python3
"""Exact check of the certified curves in `surfcert batch` answers (op intersect), independent of
surfcert: every point of every branch lies on both surfaces within 1e-12 of the curve's size
(|f| / |grad f| in exact rationals at the double point; 0 at a singular point of a surface
exactly on it), or within the doubles' floor at that point (0.87 ulp of its largest
coordinate: a rounded point cannot be nearer), and along every closed branch of a smooth curve (the answer's description says
"smooth") the sign of (grad f x grad g) . (p_{i+1} - p_{i-1}) is constant: the field is
continuous along a smooth component, and a walk that crossed a neck, or stepped onto a nearby
piece and back, reverses against it there.

Usage: check_pictures_exact.py REQUESTS.jsonl ANSWERS.jsonl [ID,ID,...]
  e.g. python3 bench/pipes_as_matrices.py --seed 29 > p.jsonl
       build/app/surfcert batch --threads 1 < p.jsonl > a.jsonl
       /usr/bin/python3 bench/check_pictures_exact.py p.jsonl a.jsonl
Surfaces given as {"matrix": ...} (doubles read exactly, the symmetric part) or as equations.
Prints one line per flagged answer, then "checked N, bad M"; exit status 1 when M > 0.
"""
import json, math, sys
from fractions import Fraction as F
import sympy as sp
X,Y,Z=sp.symbols('x y z')
def to_matrix(s):
    if isinstance(s, dict) and 'matrix' in s:
        m=[[F(v) for v in row] for row in s['matrix']]
        return [[(m[i][j]+m[j][i])/2 for j in range(4)] for i in range(4)]
    eq=s if isinstance(s,str) else s['equation']
    l,r=eq.split('=')
    e=sp.expand(sp.sympify(l.replace('^','**'))-sp.sympify(r.replace('^','**')))
    P=sp.Poly(e,X,Y,Z)
    m=[[F(0)]*4 for _ in range(4)]
    for (i,j,k),c in P.terms():
        c=F(int(sp.fraction(c)[0]),int(sp.fraction(c)[1]))
        deg=(i,j,k)
        idx=[0]*i+[1]*j+[2]*k
        if len(idx)==2:
            a,b=idx
            if a==b: m[a][a]+=c
            else: m[a][b]+=c/2; m[b][a]+=c/2
        elif len(idx)==1: m[idx[0]][3]+=c/2; m[3][idx[0]]+=c/2
        else: m[3][3]+=c
    return m
def grad(m,x):  # half gradient
    return [m[i][0]*x[0]+m[i][1]*x[1]+m[i][2]*x[2]+m[i][3] for i in range(3)]
def form(m,x):
    g=grad(m,x); return g[0]*x[0]+g[1]*x[1]+g[2]*x[2]+m[3][0]*x[0]+m[3][1]*x[1]+m[3][2]*x[2]+m[3][3]
def dist(m,x):
    g=grad(m,x); n=2*float(g[0]**2+g[1]**2+g[2]**2)**0.5
    if n>0: return abs(float(form(m,x)))/n
    return 0.0 if form(m,x)==0 else float('inf')  # a singular point of the surface, exactly on it
reqs={}
for l in open(sys.argv[1]):
    r=json.loads(l); reqs[r['id']]=r
bad=0; checked=0
for l in open(sys.argv[2]):
    r=json.loads(l)
    if r['status']!='certified': continue
    if len(sys.argv)>3 and str(r['id']) not in sys.argv[3].split(','): continue
    q=reqs[r['id']]; A=to_matrix(q['a']); B=to_matrix(q['b'])
    res=r['result']; brs=res.get('branches',[])
    pts=[p for b in brs for p in b['points']]
    if not pts: continue
    size=max(max(p[k] for p in pts)-min(p[k] for p in pts) for k in range(3))
    # The orientation test is for smooth curves (the field vanishes at a singular point of the
    # curve and flips through it): answers whose description says "smooth".
    smooth=str(res.get('description','')).startswith('smooth')
    checked+=1; msgs=[]
    for bi,b in enumerate(brs):
        xs=[[F(v) for v in p] for p in b['points']]
        # Within 1e-12 of the curve's size, or at the doubles' own floor: a double point is at
        # best half an ulp per coordinate from the exact curve, sqrt(3)/2 ulp(|x|) in all (a
        # loop 8e-7 across at |x| ~ 2.7, near a tangency, cannot be nearer than ~4e-16 to it).
        def floor(x):
            return 0.87*math.ulp(max(abs(float(v)) for v in x))
        bad_pt=[x for x in xs if max(dist(A,x),dist(B,x))>max(1e-12*size,floor(x),1e-300)]
        dmax=max(max(dist(A,x),dist(B,x)) for x in xs)
        if bad_pt: msgs.append(f"branch {bi} off surfaces {dmax:.3g} (size {size:.3g})")
        def tangent(x):
            gf=grad(A,x); gg=grad(B,x)
            return [gf[1]*gg[2]-gf[2]*gg[1], gf[2]*gg[0]-gf[0]*gg[2], gf[0]*gg[1]-gf[1]*gg[0]]
        # A vertex where grad f x grad g vanishes exactly is a singular point of the curve (a
        # crunode, a cusp, a tangency point, an apex) inserted exactly: the orientation flips
        # there by nature, and the branch is not checked for it.
        singular_vertex=any(all(v==0 for v in tangent(x)) for x in xs)
        if b['closed'] and smooth and not singular_vertex and len(xs)>=3:
            n=len(xs); first=None; rev=0
            for i in range(n):
                c=tangent(xs[i])
                pv=xs[(i-1)%n]; nx=xs[(i+1)%n]
                d=sum(c[k]*(nx[k]-pv[k]) for k in range(3))
                s=(d>0)-(d<0)
                if first is None: first=s
                if s!=first or s==0: rev+=1
            if rev: msgs.append(f"branch {bi} orientation reversed at {rev}/{n}")
    if msgs: bad+=1; print(r['id'], q.get('label'), msgs)
print(f"checked {checked}, bad {bad}")
sys.exit(1 if bad else 0)
