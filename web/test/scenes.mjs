// Scenes the project has never seen elsewhere (not in scenarios/, tests/
// or the lessons), and the settings the tests render them at: the Node
// test and the browser test render each in the WebAssembly build and
// compare it with the native renderer's bytes.

export const unseenScenes = [
  {
    name: "mirror-corridor",
    settings: { width: 160, height: 120, depth: 7, samples: 1, time: 0 },
    text: `camera distance 12 angle 0.9 end
ambient 0.15
light vector 0.3, 0, 0.6 intensity 0.9 end
proc row(k)
  if k < 6 then
    put sphere center -3 + 1.2 * k, -0.5 + 0.3 * sin(k), -2 * k radius 0.5
          kd 0.5 ks 0.5 phong 60 color 40 * k, 255 - 30 * k, 120
        end
    row(k + 1)
  end
end
row(0)
put plane rotation 0, 0, 0 shift -1.2 kd 0.4 ks 0.6 phong 200 color 200, 200, 220 end
put box center 5, 0, -4 length 0.2, 6, 12 kd 0.1 ks 0.9 phong 500 color 255, 255, 255 end
`,
  },
  {
    name: "spinning-tower",
    settings: { width: 120, height: 160, depth: 3, samples: 4, time: 5 },
    text: `camera distance 14 angle 0.8 end
ambient 0.3
light rotation 0.9, 0.4, 0 intensity 0.7 end
proc floor(n)
  if n < 8 then
    put translate
          rotate box center 0, 0, 0 length 2 - 0.2 * n, 0.5, 2 - 0.2 * n
                   kd 0.8 ks 0.2 phong 20 color 255 - 25 * n, 90 + 20 * n, 60
                 end
          by 0, 0.2 * n * time, 0 end
        by 0, -3 + 0.6 * n, 0 end
    floor(n + 1)
  end
end
floor(0)
`,
  },
  {
    name: "scaled-group",
    settings: { width: 200, height: 100, depth: 5, samples: 1, time: 0 },
    text: `camera distance 9 angle 1.2 end
ambient 0.2
light vector -0.4, 0, 0.4 intensity 0.6 end
light vector 0.6, 0.3, 0 intensity 0.4 end
object pair = group
  sphere center -1, 0, 0 radius 0.8 kd 0.7 ks 0.3 phong 40 color 250, 200, 30 end
  sphere center 1, 0, 0 radius 0.8 kd 0.7 ks 0.3 phong 40 color 30, 120, 250 end
end
put translate scale pair by 0.5 end by -2.5, 0, 0 end
put pair
put translate scale pair by 1.5 end by 3, 0.5, -3 end
let high = sqrt(2) * pi
put plane rotation 0, 0, 0 shift -high kd 0.9 ks 0 phong 1 color 90, 160, 90 end
`,
  },
];
