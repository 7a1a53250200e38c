//VTK::System::Dec
//VTK::Output::Dec

// ProxyGI image-space GI, receiver buffer at 1/pgiScale of the window: one
// full-resolution receiver per pgiScale x pgiScale block (its centre), as
// if the scene were rasterised at the lower resolution, moved to world
// coordinates (proxies and light live there).
in vec2 texCoord;
uniform sampler2D pgiGPosition; // view-space xyz, w = 1 on receivers
uniform sampler2D pgiGNormal;   // view-space normal
uniform sampler2D pgiGDepth;
uniform int pgiScale;
uniform mat4 pgiVCToWC;
uniform mat3 pgiNormalVCToWC;

void main()
{
  ivec2 size = textureSize(pgiGPosition, 0);
  ivec2 low = (size + ivec2(pgiScale - 1)) / pgiScale;
  ivec2 src = min(ivec2(texCoord * vec2(low)) * pgiScale + ivec2(pgiScale / 2), size - ivec2(1));
  vec4 p = texelFetch(pgiGPosition, src, 0);
  float depth = texelFetch(pgiGDepth, src, 0).r;
  if (!(depth < 1.0) || !(p.w > 0.5))
  {
    gl_FragData[0] = vec4(0.0);
    gl_FragData[1] = vec4(0.0);
    return;
  }
  vec3 n = pgiNormalVCToWC * texelFetch(pgiGNormal, src, 0).xyz;
  float len = length(n);
  // xyz: world position, w: eye depth; xyz: world normal, w: 1 = receiver.
  gl_FragData[0] = vec4((pgiVCToWC * vec4(p.xyz, 1.0)).xyz, -p.z);
  gl_FragData[1] = vec4(len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0), 1.0);
}
