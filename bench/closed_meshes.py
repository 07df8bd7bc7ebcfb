"""Closed test meshes for the cutting table of docs/cutting.md, written as OBJ into DIR:
sphere.obj (UV sphere R 50, 12 x 24, 528 triangles), torus.obj (R 50 / 20, 16 x 16 quads, 512),
capcyl.obj (capped cylinder R 30, h 80, 24 around, 8 rows, 4 lid rings, 720), box.obj
(60 x 40 x 30, 6 x 6 squares a face, 432), tetrahedron.obj (4).

Usage: python3 bench/closed_meshes.py DIR
"""
import math, os, sys
def write(path, V, F):
    with open(path, "w") as f:
        for v in V: f.write("v %.9f %.9f %.9f\n" % v)
        for t in F: f.write("f %d %d %d\n" % (t[0]+1, t[1]+1, t[2]+1))
def sphere(R=50.0, rings=12, seg=24):
    V=[(0,0,R)]
    for i in range(1,rings):
        th=math.pi*i/rings
        for j in range(seg):
            ph=2*math.pi*j/seg
            V.append((R*math.sin(th)*math.cos(ph),R*math.sin(th)*math.sin(ph),R*math.cos(th)))
    V.append((0,0,-R)); S=len(V)-1
    idx=lambda i,j: 1+(i-1)*seg+(j%seg)
    F=[]
    for j in range(seg): F.append((0, idx(1,j), idx(1,j+1)))
    for i in range(1,rings-1):
        for j in range(seg):
            a,b,c,d=idx(i,j),idx(i+1,j),idx(i+1,j+1),idx(i,j+1)
            F.append((a,b,c)); F.append((a,c,d))
    for j in range(seg): F.append((S, idx(rings-1,j+1), idx(rings-1,j)))
    return V,F
def torus(n=16, Rm=50.0, r=20.0):
    V=[]
    for i in range(n):
        for j in range(n):
            u=2*math.pi*i/n; v=2*math.pi*j/n; rad=Rm+r*math.cos(v)
            V.append((rad*math.cos(u),rad*math.sin(u),r*math.sin(v)))
    idx=lambda i,j:(i%n)*n+(j%n)
    F=[]
    for i in range(n):
        for j in range(n):
            F.append((idx(i,j),idx(i+1,j),idx(i+1,j+1))); F.append((idx(i,j),idx(i+1,j+1),idx(i,j+1)))
    return V,F
def capped_cylinder(R=30.0, H=80.0, seg=24, rows=8, cap_rings=4):
    # side rings z=0..H, caps as concentric rings to centre
    V=[]; F=[]
    def ring(r,z):
        s=len(V)
        for j in range(seg):
            a=2*math.pi*j/seg; V.append((r*math.cos(a),r*math.sin(a),z))
        return s
    side=[ring(R,H*k/rows) for k in range(rows+1)]
    def strip(a,b,flip):
        for j in range(seg):
            p,q,r_,s=a+j,a+(j+1)%seg,b+(j+1)%seg,b+j
            if flip: F.append((p,r_,q)); F.append((p,s,r_))
            else: F.append((p,q,r_)); F.append((p,r_,s))
    for k in range(rows): strip(side[k],side[k+1],False)
    for z,top in ((0.0,False),(H,True)):
        prev=side[-1] if top else side[0]
        for k in range(1,cap_rings):
            cur=ring(R*(cap_rings-k)/cap_rings,z)
            strip(prev,cur,not top) if not top else strip(prev,cur,False)
            prev=cur
        c=len(V); V.append((0,0,z))
        for j in range(seg):
            a,b=prev+j,prev+(j+1)%seg
            F.append((a,b,c) if top else (b,a,c))
    return V,F
def box(sx,sy,sz,n):
    X=(1,0,0);Y=(0,1,0);Z=(0,0,1)
    def mul(v,k): return tuple(c*k for c in v)
    def add(a,b): return tuple(x+y for x,y in zip(a,b))
    O=(0,0,0)
    faces=[(O,mul(Y,sy),mul(X,sx)),(mul(Z,sz),mul(X,sx),mul(Y,sy)),(O,mul(X,sx),mul(Z,sz)),(mul(Y,sy),mul(Z,sz),mul(X,sx)),(O,mul(Z,sz),mul(Y,sy)),(mul(X,sx),mul(Y,sy),mul(Z,sz))]
    V=[];F=[]
    def idx(p):
        for i,q in enumerate(V):
            if sum((a-b)**2 for a,b in zip(p,q))<1e-18: return i
        V.append(p); return len(V)-1
    for o,u,v in faces:
        at=lambda i,j: add(add(o,mul(u,i/n)),mul(v,j/n))
        for i in range(n):
            for j in range(n):
                a,b,c,d=idx(at(i,j)),idx(at(i+1,j)),idx(at(i+1,j+1)),idx(at(i,j+1))
                F.append((a,b,c));F.append((a,c,d))
    return V,F
def tetrahedron():
    return [(0,0,0),(1,0,0),(0,1,0),(0,0,1)],[(0,2,1),(0,1,3),(1,2,3),(0,3,2)]
if __name__=="__main__":
    d=sys.argv[1]; os.makedirs(d, exist_ok=True)
    for name,fn in (("sphere",sphere),("torus",torus),("capcyl",capped_cylinder),
                    ("box",lambda: box(60,40,30,6)),("tetrahedron",tetrahedron)):
        V,F=fn(); write("%s/%s.obj"%(d,name),V,F); print(name,len(F))
