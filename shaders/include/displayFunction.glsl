// The display transform as a function, vec4 hdhairDisplay(vec4): scene-linear
// RGB (un-premultiplied, or over black) in, display code values out, alpha
// kept. This file is the identity, so that displayTransform.frag compiles on
// its own; at run time hdHair/image/DisplayTransform.cpp writes the real one
// (the sRGB curve, or the GLSL OpenColorIO generates for a display and view)
// and gl::DisplayTransformPass puts it in this file's place.
vec4 hdhairDisplay(vec4 color) { return color; }
