//VTK::System::Dec

// The GI compute pass rasterises nothing (GL_RASTERIZER_DISCARD); a
// program still needs a fragment stage.

//VTK::Output::Dec

void main()
{
  gl_FragData[0] = vec4(0.0);
}
