//VTK::System::Dec

// Test harness: runs one GLSL helper of pgiGILibrary.glsl per vertex on
// inputs given as vec4 attributes and captures its vec4 outputs by transform
// feedback, so each helper can be compared with its C++ twin.

//PGI::Defines

//PGI::Library

//PGI::Harness::Dec

void main()
{
  //PGI::Harness::Impl
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
