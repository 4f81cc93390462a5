#!/usr/bin/env python3
"""A probe, in doubles, of the fold-pair clause (docs/campaign.md, "At 1920x1080: a second finding,
and the fold-pair clause"; reference/exact_image.cpp decides it exactly); a developer's check.

For the first light of a scene of OFF meshes and one pixel: every casting edge uv (of triangle t,
not the one the centre ray hits first) whose projection passes within RHO px of the pixel centre
(GL's subpixel precision: 1/256 px) is listed with the ray parameters where the plane of t (its
cap) and the plane of its side face (L, u, v) cross the rays through the centre and four points
RHO px around it. The pixel is AMBIGUOUS when either face's range reaches P or the two lie on
opposite sides of P: rounding decides whether the pair covers the centre, and then the count.

  python3 tools/fold_pair_probe.py 0.00390625    # the two gl_fold pixels (ambiguous) and the pertri_edge_on_pair pixels (decided)
"""
import json, math, sys, os
def sub(a,b): return [x-y for x,y in zip(a,b)]
def add(a,b): return [x+y for x,y in zip(a,b)]
def mul(a,s): return [x*s for x in a]
def dot(a,b): return sum(x*y for x,y in zip(a,b))
def cross(a,b): return [a[1]*b[2]-a[2]*b[1],a[2]*b[0]-a[0]*b[2],a[0]*b[1]-a[1]*b[0]]
def norm(a): n=math.sqrt(dot(a,a)); return mul(a,1/n)
def read_off(p):
    w=open(p).read().split(); assert w[0]=='OFF'; n,m=int(w[1]),int(w[2]); k=4
    V=[[float(w[k+3*i+j]) for j in range(3)] for i in range(n)]; k+=3*n; T=[]
    for i in range(m):
        c=int(w[k]); T.append([int(x) for x in w[k+1:k+1+c]]); k+=1+c
    return V,T
def run(scene_path, px, py, rho):
    sc=json.load(open(scene_path)); d0=os.path.dirname(scene_path)
    cam=sc['camera']; E=cam['eye']; T=cam['target']; UP=cam.get('up',[0,1,0]); W,H=cam['size']; fov=cam['fov_y_deg']
    L=sc['lights'][0]
    tris=[]
    for m in sc['meshes']:
        V,F=read_off(os.path.join(d0,m['file']))
        for f in F: tris.append(([V[i] for i in f], m.get('casts',True), m['name']))
    f=norm(sub(T,E)); r=norm(cross(f,UP)); u=cross(r,f); th=math.tan(math.radians(fov)/2); asp=W/H
    def ray(x,y): return norm(add(add(f,mul(r,(2*x/W-1)*th*asp)),mul(u,(1-2*y/H)*th)))
    def proj(X):  # pixel coordinates of point X
        D=sub(X,E); z=dot(D,f); return ((dot(D,r)/z/(th*asp)+1)*W/2, (1-dot(D,u)/z/th)*H/2), z
    d=ray(px+0.5,py+0.5)
    best=None
    for k,(t,c,n) in enumerate(tris):
        a,b,cc=t; e1=sub(b,a); e2=sub(cc,a); p=cross(d,e2); det=dot(e1,p)
        if abs(det)<1e-300: continue
        s=sub(E,a); uu=dot(s,p)/det; q=cross(s,e1); vv=dot(d,q)/det; tt=dot(e2,q)/det
        if uu>=0 and vv>=0 and uu+vv<=1 and tt>0 and (best is None or tt<best[0]): best=(tt,k)
    tp,h=best; P=add(E,mul(d,tp))
    def plane_t(a,b,c): # ray param crossing of plane through a,b,c
        n=cross(sub(b,a),sub(c,a)); den=dot(n,d)
        return None if den==0 else dot(n,sub(a,E))/den
    out=[]
    for k,(t,c,n) in enumerate(tris):
        if not c or k==h: continue
        for i in range(3):
            U,V=t[i],t[(i+1)%3]
            (pu,zu),(pv,zv)=proj(U),proj(V)
            if zu<=0 or zv<=0: continue
            # distance in pixels from the centre to the projected segment
            C=(px+0.5,py+0.5); A=pu; B=pv; AB=(B[0]-A[0],B[1]-A[1]); AC=(C[0]-A[0],C[1]-A[1])
            l2=AB[0]**2+AB[1]**2; s=max(0,min(1,(AC[0]*AB[0]+AC[1]*AB[1])/l2)) if l2>0 else 0
            dist=math.hypot(A[0]+s*AB[0]-C[0],A[1]+s*AB[1]-C[1])
            if dist>rho: continue
            tc=plane_t(*t); ts=plane_t(U,V,L[:3])
            # each plane's crossing over the centre's disc of radius rho (4 offset rays)
            def crossing_range(pl):
                vals=[]
                for dx,dy in ((0,0),(rho,0),(-rho,0),(0,rho),(0,-rho)):
                    dd=ray(px+0.5+dx,py+0.5+dy); n=cross(sub(pl[1],pl[0]),sub(pl[2],pl[0])); den=dot(n,dd)
                    vals.append(float('inf') if den==0 else dot(n,sub(pl[0],E))/den)
                return min(vals),max(vals)
            rc=crossing_range(t); rs=crossing_range([U,V,L[:3]])
            def side(rg):  # -1 all in front of P, +1 all behind (or behind the eye), 0 reaches P
                lo,hi=rg
                if lo>tp or hi<0: return 1
                if hi<tp and lo>0: return -1
                return 0
            straddle = side(rc)==0 or side(rs)==0 or side(rc)!=side(rs)
            tc=(tc,rc); ts=(ts,rs)
            out.append((k,n,i,dist,tc,ts,straddle))
    print(os.path.basename(scene_path),(px,py),'P t=%.5f on tri %d'%(tp,h))
    for o in out: print('   tri %d (%s) edge %d: %.2e px, cap plane t=%s side plane t=%s straddle=%s'%(o[0],o[1],o[2],o[3],o[4],o[5],o[6]))
    return any(o[6] for o in out)
if __name__=='__main__':
    rho=float(sys.argv[1])
    for path,x,y in [('tests/regressions/gl_fold/all_methods_1920x1080_s2_c7.json',739,657),('tests/regressions/gl_fold/all_methods_1920x1080_s2_c9.json',970,748),
                     ('tests/regressions/gl/pertri_edge_on_pair_1024x768.json',83,463),('tests/regressions/gl/pertri_edge_on_pair_1920x1080.json',1081,430)]:
        print('AMBIGUOUS' if run(path,x,y,rho) else 'decided')
