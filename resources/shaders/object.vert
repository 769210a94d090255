#version 410 core
// Objects: world position and normal for the per-fragment lookup direction.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;  // the model's rotation (scale is uniform, see scene.h)
uniform mat4 uViewProjection;

out vec3 vWorldPosition;
out vec3 vNormal;

void main() {
    vec4 world = uModel * vec4(aPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = uNormalMatrix * aNormal;
    gl_Position = uViewProjection * world;
}
