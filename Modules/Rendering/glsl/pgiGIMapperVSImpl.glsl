//VTK::Color::Impl
  pgiRadianceVSOutput = pgiRadianceMC.rgb;
