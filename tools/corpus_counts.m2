-- Independent solution counts of templates/classic/*.mp: each system written again in
-- Macaulay2 with random rational data; `degree` of the ideal is the number of solutions.
-- Run: M2 --script tools/corpus_counts.m2 (Macaulay2 is not a dependency of the build).
setRandomSeed 12;
rq = () -> (random(-1000,1000))/(random(1,997));
pt = () -> matrix{{rq()},{rq()},{1_QQ}};
v3 = () -> matrix{{rq()},{rq()},{rq()}};
m3 = () -> matrix table(3,3,(i,j)->rq());
sk = v -> matrix{{0,-v_(2,0),v_(1,0)},{v_(2,0),0,-v_(0,0)},{-v_(1,0),v_(0,0),0}};
-- rotation (exact, rational) from the Cayley transform
rot = () -> (s := v3(); S := sk(s); I3 := id_(QQ^3); (I3 - S)^-1 * (I3 + S));
report = (name, I) -> print(name | ": dim " | toString(dim I) | ", degree " | toString(degree I));
sc = M -> M_(0,0);

-- relpose_7pt
R = QQ[x]; F1 = sub(m3(),R); F2 = sub(m3(),R);
report("relpose_7pt", ideal det(x*F1+F2));

-- p3p
R = QQ[d1,d2,d3]; bD = apply(3,i->sub(pt(),R)); sD = apply(3,i->sub(rq(),R)); dD = {d1,d2,d3};
uD = (i,j) -> dD_i*bD_i - dD_j*bD_j;
report("p3p", ideal(sc(transpose uD(0,1) * uD(0,1)) - sD_0, sc(transpose uD(0,2)*uD(0,2)) - sD_1, sc(transpose uD(1,2)*uD(1,2)) - sD_2));

-- gp3p
R = QQ[d1,d2,d3]; cD = apply(3,i->sub(v3(),R)); bD = apply(3,i->sub(v3(),R)); sD = apply(3,i->sub(rq(),R)); dD = {d1,d2,d3};
uD = (i,j) -> (cD_i + dD_i*bD_i) - (cD_j + dD_j*bD_j);
report("gp3p", ideal(sc(transpose uD(0,1) * uD(0,1)) - sD_0, sc(transpose uD(0,2)*uD(0,2)) - sD_1, sc(transpose uD(1,2)*uD(1,2)) - sD_2));

-- relpose_upright_3pt (and the projection to (c, s) for the eliminate-t version)
R = QQ[c,s,t1,t2,t3]; x1D = apply(3,i->sub(pt(),R)); x2D = apply(3,i->sub(pt(),R));
Ry = matrix{{c,0,s},{0,1,0},{-s,0,c}}; tD = matrix{{t1},{t2},{t3}};
I = ideal(apply(3,k->sc(transpose x2D_k * sk(tD) * Ry * x1D_k))) + ideal(c^2+s^2-1, t1^2+t2^2+t3^2-1);
report("relpose_upright_3pt", I);
report("relpose_upright_3pt_elim (t eliminated)", eliminate({t1,t2,t3}, I));
-- relpose_upright_3pt_tan (q = tan of the half yaw, t eliminated, saturated by 1 + q^2)
R = QQ[q,t1,t2,t3]; x1D = apply(3,i->sub(pt(),R)); x2D = apply(3,i->sub(pt(),R));
Ryq = matrix{{1-q^2,0,2*q},{0,1+q^2,0},{-2*q,0,1-q^2}}; tD = matrix{{t1},{t2},{t3}};
I = ideal(apply(3,k->sc(transpose x2D_k * sk(tD) * Ryq * x1D_k))) + ideal(t1^2+t2^2+t3^2-1);
report("relpose_upright_3pt_tan (t eliminated, saturated, in q)", sub(saturate(eliminate({t1,t2,t3}, I), ideal(1+q^2)), QQ[q]));

-- relpose_5pt
R = QQ[x,y,z]; E = x*sub(m3(),R) + y*sub(m3(),R) + z*sub(m3(),R) + sub(m3(),R);
I = ideal(det E) + ideal flatten entries (2*E*transpose(E)*E - trace(E*transpose E)*E);
report("relpose_5pt", I);

-- relpose_6pt_focal
R = QQ[x,y,w]; F = x*sub(m3(),R) + y*sub(m3(),R) + sub(m3(),R); Q = matrix{{1,0,0},{0,1,0},{0,0,w}};
I = ideal(det F) + ideal flatten entries (2*F*Q*transpose(F)*Q*F - trace(F*Q*transpose(F)*Q)*F);
report("relpose_6pt_focal", I);

-- relpose_6pt_onefocal
R = QQ[x,y,w]; F = x*sub(m3(),R) + y*sub(m3(),R) + sub(m3(),R); Q = matrix{{1,0,0},{0,1,0},{0,0,w}};
I = ideal(det F) + ideal flatten entries (2*F*transpose(F)*Q*F - trace(F*transpose(F)*Q)*F);
report("relpose_6pt_onefocal", I);

-- grsrp_gravity_lin (and its projection to a)
R = QQ[a,t1,t2,t3]; x1D = apply(3,i->sub(pt(),R)); x2D = apply(3,i->sub(pt(),R));
v1D = apply(3,i->sub(rq(),R)); v2D = apply(3,i->sub(rq(),R));
w1D = sub(v3(),R); w2D = sub(v3(),R); R0 = sub(rot(),R); gD = sub(v3(),R);
tD = matrix{{t1},{t2},{t3}}; I3 = id_(R^3);
I = ideal(apply(3,k->sc(transpose x2D_k * sk(tD) * (I3 + v2D_k*sk(w2D)) * R0 * (I3 + a*sk(gD)) * (I3 - v1D_k*sk(w1D)) * x1D_k))) + ideal(t1^2+t2^2+t3^2-1);
report("grsrp_gravity_lin", I);
report("grsrp_gravity_lin_elim (t eliminated)", eliminate({t1,t2,t3}, I));

-- p3ll (quaternion (1,b,c,d); saturating by 1 + b^2 + c^2 + d^2 changes nothing)
R = QQ[b,c,d];
Rq = matrix{{1+b^2-c^2-d^2, 2*(b*c-d), 2*(b*d+c)},{2*(b*c+d), 1-b^2+c^2-d^2, 2*(c*d-b)},{2*(b*d-c), 2*(c*d+b), 1-b^2-c^2+d^2}};
lD = apply(3,i->sub(v3(),R)); VD = apply(3,i->sub(v3(),R));
I = ideal(apply(3,j->sc(transpose lD_j * Rq * VD_j)));
report("p3ll", I);
report("p3ll (saturated by 1 + b^2 + c^2 + d^2)", saturate(I, ideal(1+b^2+c^2+d^2)));

-- rotation_2pt_focal
R = QQ[w]; pD = apply(2,i->sub(pt(),R)); qD = apply(2,i->sub(pt(),R));
dtD = (u,v) -> sc(transpose u * v) - 1 + w;
report("rotation_2pt_focal", ideal((dtD(pD_0,pD_1))^2*dtD(qD_0,qD_0)*dtD(qD_1,qD_1) - (dtD(qD_0,qD_1))^2*dtD(pD_0,pD_0)*dtD(pD_1,pD_1)));

-- p35pf (quaternion, z saturation), count only
R = QQ[b,c,d,l,f,z];
Rq = matrix{{1+b^2-c^2-d^2, 2*(b*c-d), 2*(b*d+c)},{2*(b*c+d), 1-b^2+c^2-d^2, 2*(c*d-b)},{2*(b*d-c), 2*(c*d+b), 1-b^2-c^2+d^2}};
xD = apply(4,i->sub(pt(),R)); XD = apply(4,i->sub(v3(),R));
rayD = i -> matrix{{xD_i_(0,0)},{xD_i_(1,0)},{f}};
YD = i -> Rq*(XD_i - XD_0) + l*rayD(0);
I = ideal(apply({1,2,3}, i->(rayD(i))_(1,0)*(YD(i))_(2,0) - (rayD(i))_(2,0)*(YD(i))_(1,0))) + ideal(apply({1,2}, i->(rayD(i))_(2,0)*(YD(i))_(0,0) - (rayD(i))_(0,0)*(YD(i))_(2,0))) + ideal(z*(1+b^2+c^2+d^2)-1);
report("p35pf", I);

-- p35pf_nullspace (P = N [x, 1]: the four quadrics of M M' and the cubics of M' diag(1,1,f^2) M)
R = QQ[x1,x2,x3,x4]; ND = sub(matrix table(12,5,(i,j)->rq()), R);
pD = ND * matrix{{x1},{x2},{x3},{x4},{1_R}};
rowD = k -> matrix{{pD_(k,0)},{pD_(k+3,0)},{pD_(k+6,0)}};
aD = rowD(0); bD = rowD(1); cD = rowD(2);
HD = aD * transpose aD + bD * transpose bD - sc(transpose bD * bD) * id_(R^3);
I = ideal(sc(transpose aD * bD), sc(transpose aD * cD), sc(transpose bD * cD), sc(transpose aD * aD - transpose bD * bD)) + ideal flatten apply(3, i -> apply({{0,1},{0,2},{1,2}}, jk -> HD_(i,jk_0) * cD_(jk_1,0) - HD_(i,jk_1) * cD_(jk_0,0)));
report("p35pf_nullspace", I);

-- p2p2pl_canonical (the canonical frames: R = Ry(c) Rx(b), t = (0, 0, (u (1 - c^2) + 2 c) / (1 + c^2)))
R = QQ[b,c]; uD = sub(rq(),R); xD = apply(2,i->sub(v3(),R)); XD = apply(2,i->sub(v3(),R)); VD = apply(2,i->sub(v3(),R));
Rx = matrix{{1+b^2,0,0},{0,1-b^2,-2*b},{0,2*b,1-b^2}}; Ry = matrix{{1-c^2,0,2*c},{0,1+c^2,0},{-2*c,0,1-c^2}}; Rq = Ry*Rx;
ez = matrix{{0_R},{0_R},{1_R}}; cr = (a, v) -> sk(a) * v;
I = ideal apply(2, j -> sc(transpose xD_j * ((1+c^2) * Rq * cr(XD_j, VD_j) + (uD*(1-c^2) + 2*c) * cr(ez, Rq*VD_j))));
report("p2p2pl_canonical", I);

-- p2p2pl (quaternion, z saturation), count only
R = QQ[b,c,d,l,z];
Rq = matrix{{1+b^2-c^2-d^2, 2*(b*c-d), 2*(b*d+c)},{2*(b*c+d), 1-b^2+c^2-d^2, 2*(c*d-b)},{2*(b*d-c), 2*(c*d+b), 1-b^2-c^2+d^2}};
xD = apply(2,i->sub(pt(),R)); XD = apply(2,i->sub(v3(),R)); yD = apply(2,i->sub(pt(),R)); PD = apply(2,i->sub(v3(),R)); VD = apply(2,i->sub(v3(),R));
TD = l*xD_0 - Rq*XD_0; YD = Rq*XD_1 + TD;
I = ideal(xD_1_(1,0)*YD_(2,0) - YD_(1,0), YD_(0,0) - xD_1_(0,0)*YD_(2,0)) + ideal(apply(2,j->sc(transpose yD_j * sk(Rq*PD_j + TD) * Rq * VD_j))) + ideal(z*(1+b^2+c^2+d^2)-1);
report("p2p2pl", I);
-- relpose_5pt_cayley (q, t; 40) and relpose_5pt_cayley_sat (t eliminated, saturated by 1 + q'q; 20)
R = QQ[q1,q2,q3,t1,t2,t3]; x1D = apply(5,i->sub(pt(),R)); x2D = apply(5,i->sub(pt(),R));
qD = matrix{{q1},{q2},{q3}}; tD = matrix{{t1},{t2},{t3}}; nq = sc(transpose qD * qD);
Rq = (1 - nq)*id_(R^3) + 2*qD*transpose(qD) + 2*sk(qD);
I = ideal(apply(5,k->sc(transpose x2D_k * sk(tD) * Rq * x1D_k))) + ideal(t1^2+t2^2+t3^2-1);
report("relpose_5pt_cayley", I);
report("relpose_5pt_cayley_sat (t eliminated, saturated)", saturate(eliminate({t1,t2,t3}, I), ideal(1 + nq)));

-- up2p
R = QQ[c,s,t1,t2,t3]; pD = apply(2,i->sub(v3(),R)); xD = apply(2,i->sub(pt(),R)); T = matrix{{t1},{t2},{t3}};
Ry = matrix{{c,0,s},{0,1,0},{-s,0,c}};
I = ideal(flatten apply(2, i -> flatten entries (sk(xD_i) * (Ry*pD_i + T)))) + ideal(c^2+s^2-1);
report("up2p", I);
report("up2p_elim (t eliminated, in c, s)", sub(eliminate({t1,t2,t3}, I), QQ[c,s]));

-- relpose_known_rotation_2pt
R = QQ[t1,t2,t3]; x1D = apply(2,i->sub(pt(),R)); x2D = apply(2,i->sub(pt(),R)); Rm = sub(rot(),R); T = matrix{{t1},{t2},{t3}};
report("relpose_known_rotation_2pt", ideal(apply(2, i -> sc(transpose x2D_i * sk(T) * Rm * x1D_i))) + ideal(t1^2+t2^2+t3^2-1));

-- relpose_5pt_entries
R = QQ[e1,e2,e3,e4,e5,e6,e7,e8]; x1D = apply(5,i->sub(pt(),R)); x2D = apply(5,i->sub(pt(),R));
Em = matrix{{e1,e2,e3},{e4,e5,e6},{e7,e8,1}};
report("relpose_5pt_entries", ideal(apply(5, i -> sc(transpose x2D_i * Em * x1D_i))) + ideal(det Em) + ideal(flatten entries (2*Em*transpose(Em)*Em - trace(Em*transpose(Em))*Em)));
-- r6p (the linearised rolling-shutter absolute pose; unknowns renamed: `v3` and `CC` are taken)
R = QQ[vx,vy,vz,wx,wy,wz,cx,cy,cz,tx,ty,tz];
vv = matrix{{vx},{vy},{vz}}; ww = matrix{{wx},{wy},{wz}}; Cv = matrix{{cx},{cy},{cz}}; tt = matrix{{tx},{ty},{tz}};
I3 = id_(R^3);
report("r6p", ideal flatten apply(6, i -> (x := sub(pt(),R); X := sub(v3(),R); u := x_(1,0);
  P := (I3 + u*sk(ww))*(I3 + sk(vv))*X + Cv + u*tt;
  {u*P_(2,0) - P_(1,0), P_(0,0) - x_(0,0)*P_(2,0)})));
exit 0
