#!/usr/bin/env python3
"""Random scenes of circular arcs and points for the incremental engine.

usage: scripts/gen_arcs.py N SEED OUT.json

N arcs (radii 0.1-0.5 / sqrt(N), spans 0.3 to 2*pi - 0.3) and N/2 points in the unit
square, kept apart by 0.25 / sqrt(N) (checked on 24 samples per arc), so that no two
sites cross or touch; epsilon 1e-4.
"""
import json, math, random, sys
n=int(sys.argv[1]); seed=int(sys.argv[2]); out=sys.argv[3]
random.seed(seed)
arcs=[]; pts=[]
def samples(c,r,a0,sp,k=24):
    return [(c[0]+r*math.cos(a0+sp*i/(k-1)), c[1]+r*math.sin(a0+sp*i/(k-1))) for i in range(k)]
cell=2.0/math.sqrt(n)
grid={}
def key(p): return (int(p[0]/cell), int(p[1]/cell))
def ok(ss, gap):
    for p in ss:
        kx,ky=key(p)
        for dx in (-1,0,1):
            for dy in (-1,0,1):
                for q in grid.get((kx+dx,ky+dy),[]):
                    if math.dist(p,q)<gap: return False
    return True
tries=0
while len(arcs)<n and tries<50*n:
    tries+=1
    r=random.uniform(0.1,0.5)/math.sqrt(n); c=(random.uniform(r,1-r),random.uniform(r,1-r))
    a0=random.uniform(0,2*math.pi); sp=random.uniform(0.3,2*math.pi-0.3)
    ss=samples(c,r,a0,sp)
    if not ok(ss, 0.25/math.sqrt(n)): continue
    for p in ss: grid.setdefault(key(p),[]).append(p)
    arcs.append({"kind":"arc","center":list(c),"radius":r,"start_angle":a0,"end_angle":a0+sp})
while len(pts)<n//2:
    p=(random.random(),random.random())
    if ok([p], 0.25/math.sqrt(n)):
        grid.setdefault(key(p),[]).append(p); pts.append({"kind":"point","at":list(p)})
json.dump({"domain":[0,0,1,1],"epsilon":1e-4,"sites":arcs+pts},open(out,"w"))
print(len(arcs),len(pts))
