// The layered material's weights (core/scene/layered.h, layerWeights), from the split-sum table
// (core/ibl/specular.h, SplitSumTable) uploaded as uSplitSum. Included by shading_plan.glsl.
uniform sampler2D uSplitSum;  // TEXTURE_UNIT_SPLIT_SUM, RG = (A, B) at the table's nodes
uniform vec3 uF0;             // mix(specular, baseColor, metallic)
uniform vec3 uDiffuseColour;  // baseColor · (1 − metallic)
uniform float uSpecularLambda;
uniform float uCoat;          // 0: no coat
uniform float uCoatLambda;

const float HALF_PI = 1.57079632679;

// A and B at λ and N·v, read bilinearly between the table's nodes as SplitSumTable::at reads them:
// s from x = 1 − √(1 − θ/(π/2)), θ = acos(N·v); t from λ / MAX_LAMBDA.
vec2 splitSum(float lambda, float cosView) {
    float theta = acos(clamp(cosView, 0.0, 1.0));
    float x = 1.0 - sqrt(max(0.0, 1.0 - theta / HALF_PI));
    float y = clamp(lambda, 0.0, MAX_LAMBDA) / MAX_LAMBDA;
    vec2 uv = vec2((x * float(SPLIT_SUM_COS_STEPS - 1) + 0.5) / float(SPLIT_SUM_COS_STEPS),
                   (y * float(SPLIT_SUM_LAMBDA_STEPS - 1) + 0.5) / float(SPLIT_SUM_LAMBDA_STEPS));
    return texture(uSplitSum, uv).rg;
}

// What each layer's lobe value is multiplied by at N·v = cosView (layered.h), for a specular
// layer of F0 `f0` at λ `specularLambda` over a base of `diffuseColour` (a texture-mapped
// material's, per fragment).
void layerWeightsOf(float cosView, vec3 f0, vec3 diffuseColour, float specularLambda, out vec3 diffuse,
                    out vec3 specular, out vec3 coat) {
    vec2 s = splitSum(specularLambda, cosView);
    vec3 specularAlbedo = f0 * s.x + s.y;
    float coatAlbedo = 0.0;
    if (uCoat > 0.0) {
        vec2 c = splitSum(uCoatLambda, cosView);
        coatAlbedo = uCoat * (COAT_F0 * c.x + c.y);
    }
    coat = vec3(coatAlbedo);
    specular = (1.0 - coatAlbedo) * specularAlbedo;
    diffuse = (1.0 - coatAlbedo) * (1.0 - specularAlbedo) * diffuseColour;
}

// The same for the material's uniforms (no maps).
void layerWeights(float cosView, out vec3 diffuse, out vec3 specular, out vec3 coat) {
    layerWeightsOf(cosView, uF0, uDiffuseColour, uSpecularLambda, diffuse, specular, coat);
}
