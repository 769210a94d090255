#version 410 core
// Objects: world position and normal for the per-fragment lookup direction.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;       // assets only (GL's default (0, 0) otherwise)
layout(location = 3) in vec4 aTangent;  // xyz, w: the bitangent's sign
layout(location = 4) in vec2 aUv1;      // glTF's TEXCOORD_1
layout(location = 5) in vec4 aColour;   // glTF's COLOR_0

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // the model's rotation (scale is uniform, see scene.h)
uniform mat4 uViewProjection;
uniform bool uMeshUv1, uMeshColours;  // whether the mesh has them (else the arrays are off)

out vec3 vWorldPosition;
out vec3 vNormal;
out vec2 vUv;
out vec4 vTangent;
out vec2 vUv1;
out vec4 vColour;

void main() {
    vec4 world = uModel * vec4(aPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = uNormalMatrix * aNormal;
    vUv = aUv;
    vUv1 = uMeshUv1 ? aUv1 : vec2(0.0);
    vColour = uMeshColours ? aColour : vec4(1.0);
    vTangent = vec4(uNormalMatrix * aTangent.xyz, aTangent.w);
    gl_Position = uViewProjection * world;
}
