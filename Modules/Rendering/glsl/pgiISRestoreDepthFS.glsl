//VTK::System::Dec
//VTK::Output::Dec

// ProxyGI image-space GI: the scene's depth written back after the Exact
// fallback's two stages (pgiISUpsampleFS), whose first one marked the
// pixels for the second with the quad's own depth. Colour writes are off.
in vec2 texCoord;
uniform sampler2D pgiGDepth;

void main()
{
  ivec2 px = ivec2(texCoord * vec2(textureSize(pgiGDepth, 0)));
  gl_FragDepth = texelFetch(pgiGDepth, px, 0).r;
  gl_FragData[0] = vec4(0.0);
}
