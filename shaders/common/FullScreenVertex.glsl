// Full-screen quad drawn by vtkOpenGLQuadHelper. Fragment shaders use gl_FragCoord (pixel centres at
// +0.5), not a texture coordinate.
in vec4 ndCoordIn;
in vec2 texCoordIn;

void main()
{
  // The helper binds both attributes and reports an error if either is optimised away; for its quad
  // texCoordIn * 2 - 1 equals ndCoordIn.xy, so using both yields the same position.
  gl_Position = vec4(0.5 * (ndCoordIn.xy + (2.0 * texCoordIn - 1.0)), 0.0, 1.0);
}
