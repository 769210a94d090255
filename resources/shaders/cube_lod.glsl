// The level of detail the GPU computes for texture(cube, r) at this fragment, from r's screen
// derivatives, by the specification (OpenGL 4.6 §8.13 "Cube Map Texture Selection" and §8.14.1
// "Scale Factor and Level of Detail"): the face is r's major axis ma; the face coordinates are
// s, t = (sc/|ma| + 1)/2; ρ = size · max(|∂(s,t)/∂x|, |∂(s,t)/∂y|) and λ = log2 ρ. Never
// textureQueryLod on a cube map: on Mesa llvmpipe it is 3.7 levels off the level texture() reads
// (docs/exact-mask.md); this agrees with the reads within 0.043 (test_cube_lod.cpp).
//
// On a face with major axis m and the other two axes a, b: s−½ and t−½ are ±½·(r_a/r_m) and
// ±½·(r_b/r_m), whose derivatives are ½·(∂r_a·r_m − r_a·∂r_m)/r_m²; the signs of the face's
// conventions do not change the lengths.
float cubeLevelOfDetail(vec3 r, float size) {
    vec3 a = abs(r);
    vec3 dx = dFdx(r), dy = dFdy(r);
    vec3 q, qx, qy;  // (r_m, r_a, r_b) and their derivatives, m the major axis
    if (a.x >= a.y && a.x >= a.z) {
        q = r.xyz; qx = dx.xyz; qy = dy.xyz;
    } else if (a.y >= a.z) {
        q = r.yxz; qx = dx.yxz; qy = dy.yxz;
    } else {
        q = r.zxy; qx = dx.zxy; qy = dy.zxy;
    }
    float m2 = q.x * q.x;
    vec2 stx = 0.5 * (qx.yz * q.x - q.yz * qx.x) / m2;
    vec2 sty = 0.5 * (qy.yz * q.x - q.yz * qy.x) / m2;
    float rho = size * max(length(stx), length(sty));
    return log2(max(rho, 1e-30));
}

// Reads the base level alone (no footprint widens the lobe), with a margin for how far the GPU's
// own computation may differ from the above: 0.043 at most on llvmpipe over every face, edge and
// footprint of test_cube_lod.cpp. A pixel within the margin of the edge is not called exact.
const float CUBE_LOD_MARGIN = 0.05;
bool readsBaseLevelOnly(vec3 r, float size) { return cubeLevelOfDetail(r, size) <= -CUBE_LOD_MARGIN; }
