// solar.pov: POV-Ray 3.7 version of benches/scenes/solar.ray at time = 0
// (a sun, an earth and its moon, a mirror floor, two mirror walls, two lights),
// for comparing rayrepl's picture and speed with POV-Ray's.
//
// Render (800 x 600, no antialiasing, linear output like rayrepl's):
//   povray +Ibenches/pov/solar.pov +O/tmp/solar_pov.png +W800 +H600 -D File_Gamma=1.0
// (+WT2 for two threads).
//
// POV-Ray is left-handed: x right, y up, z INTO the screen. rayrepl's z
// points towards the viewer, so every z (and the z of every normal and light
// direction) is negated here. Positions are computed with the same formulas
// as in solar.ray; the tilt of the orbital plane, a rotation of angle tilt
// about x in rayrepl's axes, is applied by the macro Tilt below.
//
// Materials: rayrepl's kd Ia C + kd (N.L) I C + ks (N.H)^n I C + ks reflection
// maps to ambient kd*Ia, diffuse kd, specular ks with roughness 1/n and
// metallic (highlight in the surface colour), reflection ks. Lights are
// parallel lights very far away (rayrepl's lights are directions).
// Remaining differences: rayrepl clamps the colour at every reflection
// level, POV-Ray only at the end; POV-Ray's planes are two-sided (rayrepl's
// are one-sided, but here every ray stays on the visible side of all three).

#version 3.7;

global_settings {
  assumed_gamma 1.0
  max_trace_level 6          // the primary ray + 5 reflections (rayrepl depth 5)
  adc_bailout 0.0001
  ambient_light rgb 1
}

#declare Time = 0;
#declare Ia = 0.2;           // ambient 0.2
#declare TiltAngle = 0.45;   // let tilt = 0.45

// camera distance 24 angle 1.0 (radians, horizontal)
camera {
  perspective
  location <0, 0, -24>
  look_at <0, 0, 0>
  right x * image_width / image_height
  up y
  angle degrees(1.0)
}

// A light direction of rayrepl: R(rx, ry, rz) * (0, 1, 0) with R = Mz My Mx.
#macro LightDir(RX, RY, RZ)
  #local V1 = <0, cos(RX), sin(RX)>;                                        // Mx
  #local V2 = <V1.x * cos(RY) + V1.z * sin(RY), V1.y, -V1.x * sin(RY) + V1.z * cos(RY)>; // My
  #local V3 = <V2.x * cos(RZ) - V2.y * sin(RZ), V2.x * sin(RZ) + V2.y * cos(RZ), V2.z>;  // Mz
  <V3.x, V3.y, -V3.z>        // to POV-Ray's axes
#end

// light vector 0.6, 0, 0.5 intensity 0.7 end
light_source { 1e7 * LightDir(0.6, 0, 0.5) color rgb 0.7 parallel point_at <0, 0, 0> }
// light rotation 0.7, 0, -0.45 intensity 0.4 end
light_source { 1e7 * LightDir(0.7, 0, -0.45) color rgb 0.4 parallel point_at <0, 0, 0> }

// A point given in rayrepl's axes, rotated by tilt about x (rayrepl's
// Mx(tilt)), returned in POV-Ray's axes.
#macro Tilt(X, Y, Z)
  <X, Y * cos(TiltAngle) - Z * sin(TiltAngle), -(Y * sin(TiltAngle) + Z * cos(TiltAngle))>
#end

// rayrepl's texture: kd e ks e phong e color r, g, b
#macro Tex(KD, KS, N, R, G, B)
  pigment { color rgb <R, G, B> / 255 }
  finish {
    ambient KD * Ia
    diffuse KD
    specular KS
    roughness 1 / N
    metallic
    reflection KS
  }
#end

// ---- the sun
sphere { <0, 0, 0>, 2 Tex(0.9, 0.2, 20, 255, 190, 40) }

// ---- the earth and its moon
#declare EarthA = Time * pi / 50;
#declare MoonB = Time * pi * 0.16;
#declare EX = 6 * cos(EarthA);
#declare EZ = -6 * sin(EarthA);
sphere { Tilt(EX, 0, EZ), 0.7 Tex(0.8, 0.4, 60, 40, 110, 255) }
sphere { Tilt(EX + 1.3 * cos(MoonB), 0.3 * sin(MoonB), EZ - 1.3 * sin(MoonB)), 0.3 Tex(0.8, 0.1, 10, 200, 200, 210) }

// ---- the mirrors
// floor: normal (0, 1, 0), shift -4.5
plane { <0, 1, 0>, -4.5 Tex(0.4, 0.6, 50, 90, 90, 140) }
// left wall: rayrepl normal (0.71, 0, 0.71), shift -12
plane { <sin(pi / 4), 0, -cos(pi / 4)>, -12 Tex(0.3, 0.7, 80, 120, 200, 255) }
// right wall: rayrepl normal (-0.71, 0, 0.71), shift -12
plane { <-sin(pi / 4), 0, -cos(pi / 4)>, -12 Tex(0.3, 0.7, 80, 255, 160, 220) }
