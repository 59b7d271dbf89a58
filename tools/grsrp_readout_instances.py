# Planted instances of templates/grsrp_readout.mp on simulated geometry, one per line in
# the data-slot order of `mingen inspect` (for `mingen audit --instances-from`): random
# R0, a ~ N(0, 0.05), unit t, k in [0.7, 1.3], gyro 2.5 rad/s at 30 us/row, rows in
# [0, 1000], normalised points in [-0.5, 0.5]; x2 is placed on the epipolar line of x1.
#
# Scaling: k enters only through k * v * w, whose size (rows times rad/row, about 0.04
# here) would make the template's coefficients in k differ by orders of magnitude. The
# data are written scaled so that product is of order one: rows as fractions of the frame
# height H (v / H) and w multiplied by H / s with s = H * max(|w1|, |w2|); the solver's k is
# then k * s (divide by s to get the readout scale). --raw writes v and w unscaled (k as is).
#
# Usage: python3 tools/grsrp_readout_instances.py COUNT [SEED] [--raw] [--solutions FILE] > DATA
# --solutions FILE writes the planted solution of each instance (a1 a2 a3 t1 t2 t3 k, the
# solver's k) for `mingen audit --solutions-from FILE`.
import random, math, sys
args = [a for a in sys.argv[1:]]
raw = '--raw' in args
if raw: args.remove('--raw')
solutions = None
if '--solutions' in args:
    i = args.index('--solutions'); solutions = open(args[i + 1], 'w'); del args[i:i + 2]
rng = random.Random(int(args[1]) if len(args) > 1 else 1)
def skew(v): return [[0,-v[2],v[1]],[v[2],0,-v[0]],[-v[1],v[0],0]]
def mm(A,B): return [[sum(A[i][k]*B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def mv(A,x): return [sum(A[i][k]*x[k] for k in range(3)) for i in range(3)]
def add(A,B,s=1.0): return [[A[i][j]+s*B[i][j] for j in range(3)] for i in range(3)]
I=[[1.0 if i==j else 0.0 for j in range(3)] for i in range(3)]
def rot():
    q=[rng.gauss(0,1) for _ in range(4)]; n=math.sqrt(sum(x*x for x in q)); w,x,y,z=[c/n for c in q]
    return [[1-2*(y*y+z*z),2*(x*y-w*z),2*(x*z+w*y)],[2*(x*y+w*z),1-2*(x*x+z*z),2*(y*z-w*x)],[2*(x*z-w*y),2*(y*z+w*x),1-2*(x*x+y*y)]]
n=int(args[0])
H=1000.0
for _ in range(n):
    R0=rot(); a=[rng.gauss(0,0.05) for _ in range(3)]
    t=[rng.gauss(0,1) for _ in range(3)]; nt=math.sqrt(sum(x*x for x in t)); t=[x/nt for x in t]
    k=rng.uniform(0.7,1.3); lam=3e-5; s=2.5/math.sqrt(3)
    w1=[lam*rng.gauss(0,s) for _ in range(3)]; w2=[lam*rng.gauss(0,s) for _ in range(3)]
    x1s,x2s,v1s,v2s=[],[],[],[]
    for i in range(6):
        x1=[rng.uniform(-0.5,0.5),rng.uniform(-0.5,0.5),1.0]
        v1=rng.uniform(0,1000); v2=rng.uniform(0,1000)
        M=mm(skew(t),mm(add(I,skew(w2),k*v2),mm(R0,mm(add(I,skew(a)),add(I,skew(w1),-k*v1)))))
        l=mv(M,x1)
        xx=rng.uniform(-0.5,0.5)
        if abs(l[1])>abs(l[0]): x2=[xx,-(l[0]*xx+l[2])/l[1]]
        else: x2=[-(l[1]*xx+l[2])/l[0],xx]
        x1s+=x1[:2]; x2s+=x2; v1s.append(v1); v2s.append(v2)
    if raw:
        ks=k
    else:
        sc=H*max(math.sqrt(sum(x*x for x in w)) for w in (w1,w2))
        v1s=[v/H for v in v1s]; v2s=[v/H for v in v2s]
        w1=[x*H/sc for x in w1]; w2=[x*H/sc for x in w2]; ks=k*sc
    if solutions: solutions.write(' '.join(repr(float(x)) for x in a+t+[ks])+'\n')
    row=x1s+x2s+v1s+v2s+w1+w2+[c for r in R0 for c in r]
    print(' '.join(repr(float(v)) for v in row))
