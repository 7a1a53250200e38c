// ProxyGI image-space GI, receiver setup: written into VTK's fragment shader
// after its lighting code, while vtkPGIImageSpaceGIPass renders the scene
// into its full-resolution receiver targets. PGI_RECEIVER is 1 where the
// shader has a view-space position and normal, 0 otherwise (no GI there).
// VTK turns normals of back faces towards the viewer; GI, like the
// per-vertex kernel, takes the surface's own normal (back faces win the
// depth test at some silhouette pixels).
#if PGI_RECEIVER
  gl_FragData[1] = vec4(vertexVC.xyz, 1.0);
  gl_FragData[2] = vec4(normalize(gl_FrontFacing ? normalVCVSOutput : -normalVCVSOutput), 1.0);
#else
  gl_FragData[1] = vec4(0.0);
  gl_FragData[2] = vec4(0.0);
#endif
#if PGI_ALBEDO
  gl_FragData[3] = vec4(diffuseColor, 1.0);
#else
  gl_FragData[3] = vec4(1.0);
#endif
