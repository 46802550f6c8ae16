// assets/whitted/whitted.json in POV-Ray 3.7's scene language, for the
// timing in docs/performance.md ("Ray core"): the same camera, floor,
// spheres, light and background, and the same depth of the specular tree.
// POV-Ray is only used for this measurement; it is not a dependency.
//
//   povray whitted.pov +W512 +H512 +WT2 -D +A0.0 +FN +O/tmp/whitted-pov.png         (1 sample a pixel)
//   povray whitted.pov +W512 +H512 +WT2 -D +A0.0 +AM2 +R4 +FN +O/tmp/whitted-pov.png  (antialiased)
//
// Bounce's coordinates are right-handed, POV-Ray's left-handed: the camera's
// `right -x` mirrors the picture so that the same coordinates give the same view.
// Radiometry: Bounce's point light gives irradiance I cos / d^2 and a
// diffuse surface returns rho / pi of it; POV-Ray's light is the colour
// times 2 / (1 + (d / fade_distance)^2), so 600 / pi / 2 with fade_distance
// 1 is within 1% of Bounce's 1 / d^2 at the scene's 10-14 m.

#version 3.7;

global_settings {
  assumed_gamma 1.0      // linear, as Bounce traces; sRGB on output as Bounce writes PNGs
  max_trace_level 8      // Bounce's Whitted depth (trace_params::max_depth)
  ambient_light rgb 1
}

// Bounce's one-pass ambient term: rho / pi times the ambient irradiance
// that `bounce trace --no-radiosity` takes from its coarse solution. It
// prints it ("one pass: ambient irradiance 0.07956 0.05769 0.0397" when
// this was measured); pass another with Declare=AmbientR=... etc.
#ifndef (AmbientR) #declare AmbientR = 0.07956; #end
#ifndef (AmbientG) #declare AmbientG = 0.05769; #end
#ifndef (AmbientB) #declare AmbientB = 0.0397; #end
#declare Ambient = rgb <AmbientR, AmbientG, AmbientB> / pi;

camera {
  perspective
  location <0, 1.8, -5>
  look_at <0.2, 1.3, 2.5>
  sky y
  up y
  right -x * image_width / image_height
  angle 45 // horizontal; square pictures make it Bounce's vertical 45 too
}

background { rgb <0.25, 0.45, 0.8> }

light_source {
  <-3, 10, -8>
  color rgb 600 / pi / 2
  fade_distance 1
  fade_power 2
}

// The floor: 16 x 16 m, a checker of 1 m squares (the texture's scale 16
// over the polygon's 0..1 uv). Bounce colours the square [0,1] x [0,1]
// with color0 (red); the pattern is moved half a metre up so that the
// floor's plane is not on the boundary between POV-Ray's checker cubes.
polygon {
  5, <-8, 0, -4>, <-8, 0, 12>, <8, 0, 12>, <8, 0, -4>, <-8, 0, -4>
  pigment {
    checker color rgb <0.95, 0.85, 0.1> color rgb <0.9, 0.08, 0.05>
    translate <0, 0.5, 0>
  }
  finish { ambient 0.9 * Ambient diffuse 0.9 phong 0 }  // rho 0.9 times the texture's colour
}

// The mirror: rho 0.05, kr 0.8, Phong highlight 1 with exponent 100.
// Bounce's highlight is normalised, (n + 2) / 2 of POV-Ray's unnormalised one.
sphere {
  <1, 1.6, 4>, 1.3
  pigment { rgb 1 }
  finish {
    ambient 0.05 * Ambient
    diffuse 0.05
    reflection { 0.8 }
    phong (100 + 2) / 2
    phong_size 100
  }
}

// The glass: ior 1.5, kr 0.1 and kt 0.85 weighted by Fresnel's equations
// (Bounce: kr + F kt reflected, (1 - F) kt transmitted).
sphere {
  <-0.6, 1.25, 1>, 1
  pigment { rgbt <1, 1, 1, 0.85> }
  finish {
    ambient 0
    diffuse 0
    reflection { 0.1, 0.95 fresnel on }
    conserve_energy
    phong (200 + 2) / 2
    phong_size 200
  }
  interior { ior 1.5 }
}

// Bounce's shadow rays stop at glass (no light through it: that is a
// caustic, which the Whitted tracer leaves out); POV-Ray's pass through
// transparent objects, filtered. An opaque sphere just inside the glass,
// seen by shadow rays only, gives POV-Ray the same shadow.
sphere {
  <-0.6, 1.25, 1>, 0.999
  pigment { rgb 0 }
  no_image
  no_reflection
}

