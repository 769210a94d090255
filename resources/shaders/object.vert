#version 410 core
// Objects: world position and normal for the per-fragment lookup direction.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;       // assets only (GL's default (0, 0) otherwise)
layout(location = 3) in vec4 aTangent;  // xyz, w: the bitangent's sign

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // the model's rotation (scale is uniform, see scene.h)
uniform mat4 uViewProjection;

out vec3 vWorldPosition;
out vec3 vNormal;
out vec2 vUv;
out vec4 vTangent;

void main() {
    vec4 world = uModel * vec4(aPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = uNormalMatrix * aNormal;
    vUv = aUv;
    vTangent = vec4(uNormalMatrix * aTangent.xyz, aTangent.w);
    gl_Position = uViewProjection * world;
}
