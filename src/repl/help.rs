//! `:help`: a short explanation with an example for every keyword of the
//! language and every command of the session, written for learners.

use crate::lang::suggest::closest;
use crate::lang::words::{self, Kind};

/// One help page.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Topic {
    /// The name `:help NAME` finds it by.
    pub name: &'static str,
    /// Other names that lead to the same page (`kd` leads to `texture`).
    pub aliases: &'static [&'static str],
    /// A one-line summary for the overview.
    pub summary: &'static str,
    /// The page: what it is, then an example.
    pub text: &'static str,
}

/// What `:help` alone prints.
pub(crate) const OVERVIEW: &str = "\
Type items of the .ray language one at a time, or a command starting with `:`.
Each item is added to the scene you are building; `:render` shows it.
New to the language? `:lesson` teaches it step by step, checking your scenes.
Why is a pixel the colour it is? `:pick X Y` explains it, after a `:render`.

A first scene:
    camera distance 10 angle 0.8 end
    ambient 0.2
    light vector 0.5, 0, -0.5 intensity 0.8 end
    put sphere center 0,0,0 radius 2 kd 0.7 ks 0.3 phong 20 color 255,80,40 end
    :render

An input may span several lines: the prompt shows `...sphere>` while a
`sphere` is still waiting for its `end` (a command typed meanwhile runs at
once). Ctrl-C drops the input being typed, or stops what an input does (a
render, the writing of a file: it stays as it was). Ctrl-D leaves. Tab completes
names, commands and file names.

`:help NAME` explains one of these:";

/// Groups of topics for the overview, in the order a learner meets them.
const GROUPS: &[(&str, &[&str])] = &[
    ("Learning", &[":lesson"]),
    ("Scene set-up", &["camera", "ambient", "light"]),
    ("Shapes", &["sphere", "plane", "box", "texture"]),
    ("Moving shapes", &["translate", "rotate", "scale", "group", "by", "rotation"]),
    ("Building the scene", &["put", "object", "let", "proc", "if", "conditions", "end"]),
    ("Numbers", &["numbers", "time", "functions", "pi", "comments", "print"]),
    ("Pictures", &[":render", ":save", ":anim", ":play", ":time", ":size", ":depth", ":samples", ":preview", ":pick"]),
    ("Files", &[":load", ":reload", ":watch", ":write"]),
    ("Looking inside", &[":env", ":scene", ":show", ":list", ":history"]),
    ("The session", &[":help", ":undo", ":reset", ":limits", ":quit"]),
];

/// Every help page.
pub(crate) const TOPICS: &[Topic] = &[
    Topic {
        name: "camera",
        aliases: &[],
        summary: "where the eye is and how wide it sees",
        text: "\
camera distance D angle A end
  The eye sits on the z axis at distance D from the origin and looks towards
  the origin (towards -z). A is how wide it sees, from left edge to right
  edge, in radians (0.8 is about 46 degrees; pi/2 is a quarter turn).
  A new camera replaces the old one.
Example:
  camera distance 12 angle pi/4 end",
    },
    Topic {
        name: "ambient",
        aliases: &[],
        summary: "light that reaches every surface, even in shadow",
        text: "\
ambient I
  The light that reaches every point, from nowhere in particular, between 0
  (none: shadows are black) and 1. A new ambient replaces the old one.
Example:
  ambient 0.2",
    },
    Topic {
        name: "light",
        aliases: &[],
        summary: "a far away light shining from one direction",
        text: "\
light vector RX, RY, RZ intensity I end
  A light as far away as the sun: it shines from one direction, everywhere.
  Without rotation it shines from straight above; RX, RY, RZ turn that
  direction about the x, y and z axes (radians). I is its strength, 0 to 1.
  `light rotation ...` means the same. Each light adds one more.
Example:
  light vector 0.5, 0, -0.5 intensity 0.8 end   # from above, right and front",
    },
    Topic {
        name: "sphere",
        aliases: &[],
        summary: "a ball: center and radius",
        text: "\
sphere center X, Y, Z radius R TEXTURE end
  A ball centred on the point X, Y, Z. R must be more than 0. TEXTURE says
  how it looks (see :help texture).
Example:
  put sphere center 0, 1, 0 radius 1 kd 0.7 ks 0.3 phong 30 color 200, 30, 30 end",
    },
    Topic {
        name: "plane",
        aliases: &[],
        summary: "a flat floor, wall or ceiling that goes on forever",
        text: "\
plane rotation RX, RY, RZ shift D TEXTURE end
  A flat surface without edges. Unturned it is horizontal and faces up;
  RX, RY, RZ turn it (radians). D moves it along the way it faces. It is seen
  from the side it faces only.
Example (a floor one unit below the origin):
  put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0 phong 1 color 200, 200, 200 end",
    },
    Topic {
        name: "box",
        aliases: &[],
        summary: "a box: center and sizes along x, y and z",
        text: "\
box center X, Y, Z length W, H, D TEXTURE end
  A box centred on X, Y, Z, W wide (x), H high (y) and D deep (z), its sides
  parallel to the axes until you rotate it. Every size must be more than 0.
Example:
  put box center 0, 0, 0 length 2, 1, 1 kd 0.6 ks 0.2 phong 10 color 40, 90, 220 end",
    },
    Topic {
        name: "texture",
        aliases: &[],
        summary: "how a surface looks: kd ks phong color",
        text: "\
kd KD ks KS phong N color R, G, B
  Every shape ends with these four, in this order, before its `end`:
    kd     how much light the surface spreads around (matt), 0 to 1
    ks     how shiny it is: highlights and mirror reflections, 0 to 1
    phong  how small the highlight is: 1 is broad, 100 is a pin point (more than 0)
    color  red, green, blue, each 0 to 255
Example (a shiny red ball):
  put sphere center 0, 0, 0 radius 1 kd 0.6 ks 0.4 phong 50 color 255, 0, 0 end",
    },
    Topic {
        name: "translate",
        aliases: &[],
        summary: "move an object",
        text: "\
translate OBJECT by X, Y, Z end
  The same object moved X to the right, Y up and Z towards you.
Example:
  object ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 255, 0 end
  put translate ball by 3, 0, 0 end",
    },
    Topic {
        name: "rotate",
        aliases: &[],
        summary: "turn an object about the origin",
        text: "\
rotate OBJECT by RX, RY, RZ end
  The same object turned about the origin: RX radians about the x axis, then
  RY about y, then RZ about z. To turn something on the spot, rotate it while
  it is at the origin, then translate it.
Example:
  put translate rotate box center 0, 0, 0 length 2, 1, 1 kd 1 ks 0 phong 1 color 0, 200, 0 end
      by 0, pi/4, 0 end by 0, 0, -3 end",
    },
    Topic {
        name: "scale",
        aliases: &[],
        summary: "make an object bigger or smaller",
        text: "\
scale OBJECT by K end
  The same object K times bigger, seen from the origin: its size and its
  distance to the origin are both multiplied by K. K must not be 0.
Example:
  object unit = sphere center 1, 0, 0 radius 0.5 kd 1 ks 0 phong 1 color 0, 0, 255 end
  put scale unit by 2 end      # now at 2, 0, 0 with radius 1",
    },
    Topic {
        name: "group",
        aliases: &[],
        summary: "several objects treated as one",
        text: "\
group OBJECT OBJECT ... end
  Several objects that move, turn and scale together.
Example:
  object pair = group
    sphere center -1, 0, 0 radius 0.5 kd 1 ks 0 phong 1 color 255, 0, 0 end
    sphere center 1, 0, 0 radius 0.5 kd 1 ks 0 phong 1 color 0, 0, 255 end
  end
  put translate pair by 0, 2, 0 end",
    },
    Topic {
        name: "by",
        aliases: &[],
        summary: "how much translate, rotate and scale change an object",
        text: "\
by
  Separates the object from the amount in a transformation:
    translate OBJECT by X, Y, Z end    (see :help translate)
    rotate OBJECT by RX, RY, RZ end    (see :help rotate)
    scale OBJECT by K end              (see :help scale)
Example:
  put scale ball by 0.5 end",
    },
    Topic {
        name: "rotation",
        aliases: &[],
        summary: "three angles: about x, then y, then z",
        text: "\
rotation RX, RY, RZ
  Three angles in radians: a turn of RX about the x axis, then RY about y,
  then RZ about z, each counter-clockwise when that axis points at you.
  Planes (`plane rotation ...`) and lights (`light rotation ...`) use it;
  `rotate ... by` takes the same three angles.
Example (a wall facing you, 5 units behind the origin):
  put plane rotation pi/2, 0, 0 shift -5 kd 1 ks 0 phong 1 color 90, 90, 90 end",
    },
    Topic {
        name: "put",
        aliases: &[],
        summary: "add an object to the scene",
        text: "\
put OBJECT
  Adds the object to the scene: only what is put is drawn. The object can be
  a shape, a name given with `object`, or a transformation of them. `put` also
  works inside a procedure.
Example:
  put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 255, 255 end",
    },
    Topic {
        name: "object",
        aliases: &[],
        summary: "give an object a name (without putting it)",
        text: "\
object NAME = OBJECT
  Names an object so you can use it several times. Naming it does not draw
  it: `put` does.
Example:
  object ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 128, 0 end
  put translate ball by -2, 0, 0 end
  put translate ball by 2, 0, 0 end",
    },
    Topic {
        name: "let",
        aliases: &[],
        summary: "give a number a name",
        text: "\
let NAME = EXPRESSION
  Names a number. Inside a procedure the name belongs to that call only.
Example:
  let r = 1.5
  let side = 2 * r",
    },
    Topic {
        name: "proc",
        aliases: &[],
        summary: "a procedure: instructions to run again with other numbers",
        text: "\
proc NAME(PARAM, ...) INSTRUCTIONS end
  Defines a procedure; `NAME(1, 2)` runs its instructions with the parameters
  bound to those numbers. It sees its parameters, its own lets and objects,
  and the global names; it may call itself.
Example:
  proc ball(x, r)
    put sphere center x, 0, 0 radius r kd 1 ks 0 phong 1 color 255, 200, 0 end
  end
  ball(-2, 0.5)
  ball(2, 1)",
    },
    Topic {
        name: "if",
        aliases: &[],
        summary: "do something only when a condition holds",
        text: "\
if CONDITION then INSTRUCTIONS [else INSTRUCTIONS] end
  Runs the first instructions when the condition holds, the ones after `else`
  (if any) when it does not. See :help conditions.
Example (a recursive row of balls):
  proc row(n)
    if 0 < n then
      put sphere center n * 2, 0, 0 radius 0.8 kd 1 ks 0 phong 1 color 0, 160, 255 end
      row(n - 1)
    end
  end
  row(4)",
    },
    Topic {
        name: "conditions",
        aliases: &["=", "<", "&", "|", "!", "condition"],
        summary: "comparisons and & | ! in an if",
        text: "\
A = B      A equals B exactly
A < B      A is less than B
C & D      both hold          C | D      at least one holds
!C         C does not hold    ( C )      grouping
  `!` binds tightest, then `&`, then `|`.
Example:
  if x < 0 | !(y < 3) then put ball end",
    },
    Topic {
        name: "end",
        aliases: &[],
        summary: "closes what camera, light, shapes, transformations, group, proc and if open",
        text: "\
end
  Closes the construct opened last: camera, light, sphere, plane, box,
  translate, rotate, scale, group, proc or if. While one is still open the
  prompt shows it, like `...sphere>`.
Example:
  put group
    sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end
  end",
    },
    Topic {
        name: "numbers",
        aliases: &["+", "-", "*", "/", "arithmetic", "expressions"],
        summary: "arithmetic: + - * / and parentheses",
        text: "\
Numbers are written 3 or 0.75. Expressions use + - * / and parentheses;
* and / come before + and -, and -x negates.
Example:
  let y = (1 + 2) * 3 / 4 - -1",
    },
    Topic {
        name: "time",
        aliases: &[],
        summary: "the frame number of an animation",
        text: "\
time
  A number given to you: 0 for a single image; frame k of an animation is
  computed with time = k. Change it in the session with `:time N`; `:anim`
  goes through 1, 2, 3... (or A, A + S, A + 2S... with --time-start A
  --time-step S).
Example (a ball that rises in an animation):
  put sphere center 0, time / 2, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 255 end
  :anim 10 rise.gif",
    },
    Topic {
        name: "functions",
        aliases: &[],
        summary: "sin, cos and sqrt",
        text: "\
sin(X)  cos(X)  sqrt(X)
  Sine and cosine of an angle in radians, and the square root (of a number
  that is not negative).
Example (points around a circle):
  proc around(k)
    put sphere center 3 * cos(k * pi / 4), 3 * sin(k * pi / 4), 0 radius 0.4
      kd 1 ks 0 phong 1 color 255, 255, 255 end
  end
  around(1)  around(2)  around(3)",
    },
    Topic {
        name: "pi",
        aliases: &[],
        summary: "the number pi, half a turn in radians",
        text: "\
pi
  3.14159..., half a turn in radians: pi/2 is a quarter turn.
Example:
  put rotate ball by 0, pi / 2, 0 end",
    },
    Topic {
        name: "comments",
        aliases: &["#", "comment"],
        summary: "# starts a note to the end of the line",
        text: "\
# a note
  Everything from # to the end of the line is ignored.
Example:
  ambient 0.3   # a rather bright room",
    },
    Topic {
        name: "print",
        aliases: &[],
        summary: "show values while the program runs",
        text: "\
print EXPRESSION, ...
  Shows each expression as written and its value, with the line of the
  `print`, each time it runs: `scene.ray:5: r = 2, r * 2 = 4`. A name that
  holds an object shows what the object is. At most 1000 lines are shown at a
  time. `print` is an extension of rayrepl, not of the original language.
Example:
  let r = 2
  print r, r * 2",
    },
    Topic {
        name: ":help",
        aliases: &["help"],
        summary: "this help, or help on one word",
        text: "\
:help         lists what can be explained
:help NAME    explains a keyword or a command
Example:
  :help sphere",
    },
    Topic {
        name: ":lesson",
        aliases: &["lesson", "lessons", "learn", "tutorial"],
        summary: "guided lessons, from a first sphere to an animation",
        text: "\
:lesson [N|stop]
  `:lesson` lists the lessons, from a first sphere to an animated recursive
  scene, with a mark on those you finished. `:lesson N` starts lesson N on
  a scene of its own (`:undo` twice brings yours back). Each step says what
  to build; after each input your scene is checked, whatever way you wrote
  it: a hint if something is missing, the next step when it is right. With
  pictures on, the goal is shown beside your render. Your progress is kept
  in rayrepl/lessons in your data folder (or the file RAYREPL_LESSONS
  names), and `:lesson N` goes on where you stopped. `:lesson stop` leaves.
Example:
  :lesson
  :lesson 1",
    },
    Topic {
        name: ":render",
        aliases: &["render"],
        summary: "draw the scene in the terminal",
        text: "\
:render          draws the scene here, as large as the terminal allows
:render W H      draws it W pixels wide and H high, shown fitted to the terminal
  A render taking more than half a second shows its progress; Ctrl-C stops it.
Example:
  :render 320 240",
    },
    Topic {
        name: ":pick",
        aliases: &["pick", "why"],
        summary: "why a pixel of the last picture has its colour",
        text: "\
:pick X Y    explains pixel X, Y of the last picture (:render or :save),
             X from the left and Y from the top, both from 0
  Marks the pixel on the picture and tells what the camera ray met: the
  object's kind, the `put` that placed it and the procedure calls (with
  their values) that led there; then the ambient part, each light (lit with
  its diffuse and specular parts, facing away, or in the shadow of which
  object), the reflected ray and what it met, down to the bytes of the pixel.
  With :samples N, each of the pixel's N rays, then their average.
  From the command line: rayrepl scene.ray --explain X,Y [--json]
Example:
  :render 80 60
  :pick 40 30",
    },
    Topic {
        name: ":save",
        aliases: &["save"],
        summary: "write the scene to an image file",
        text: "\
:save FILE        writes the scene at the size set by :size
:save FILE W H    writes it W pixels wide and H high
  The file name's ending picks the format: .png or .ppm (a .gif is
  an animation: see :anim).
Example:
  :save balls.png 1024 768",
    },
    Topic {
        name: ":anim",
        aliases: &["anim", "animation"],
        summary: "write an animation, with time = 1, 2, ... N",
        text: "\
:anim N FILE [OPTIONS]
  Computes the scene N times with time = 1, 2, ..., N and writes the frames.
  FILE's ending picks the format: .gif (256 colours), .apng (exact), .mp4
  or .webm (video, made by the ffmpeg program), otherwise numbered images
  (spin.png gives spin0001.png, spin0002.png, ...). Ctrl-C stops it, in
  the middle of a frame too: the numbered images written stay, each whole,
  and are named; a .gif, .apng or video is not written.
Options, as on the command line:
  --fps F              frames a second, 0.01 to 100 (default 25)
  --loop N|forever     plays in all (default: forever; a video once)
  --time-start A       the time of frame 1 (default 1)
  --time-step S        frame k has time = A + (k - 1) * S (default 1)
  --apng               one animated PNG for a .png name
Examples:
  :anim 24 spin.gif
  :anim 48 spin.apng --fps 24 --time-start 0 --time-step 0.5",
    },
    Topic {
        name: ":play",
        aliases: &["play"],
        summary: "play the animation in the terminal, until a key",
        text: "\
:play [FRAMES [FPS]]
  Computes frames 1 to FRAMES (24 unless given) like `:anim`, at the size
  of a preview, then plays them here in a loop, FPS frames a second (12
  unless given), until any key (Ctrl-C too) stops it. Needs a terminal
  with pictures on (see `:preview`); `:anim` writes the frames to a file.
Example:
  put sphere center 3 * sin(time / 2), 0, 0 radius 1 kd 0.8 ks 0.2 phong 20 color 255, 120, 40 end
  :play 24 12",
    },
    Topic {
        name: ":time",
        aliases: &[],
        summary: "set the value of time",
        text: "\
:time N
  Sets `time` to N for what you type next and for renders; what you typed
  before that reads `time` is computed again. `:time` alone shows it.
Example:
  :time 5",
    },
    Topic {
        name: ":size",
        aliases: &["size"],
        summary: "set the image size for :save and :anim",
        text: "\
:size W H
  Sets the width and height, in pixels, of the images :save and :anim write.
  `:size` alone shows them.
Example:
  :size 800 600",
    },
    Topic {
        name: ":depth",
        aliases: &["depth"],
        summary: "set how many mirror reflections are followed",
        text: "\
:depth N
  How many times a ray may bounce off shiny (ks > 0) surfaces. 0 turns
  reflections off; the default is 5. `:depth` alone shows it.
Example:
  :depth 2",
    },
    Topic {
        name: ":samples",
        aliases: &["samples"],
        summary: "set how many rays each pixel averages (smoother edges)",
        text: "\
:samples N
  Each pixel averages N rays: 1 is fastest, 4 or more smooths jagged edges
  but takes N times as long. `:samples` alone shows it.
Example:
  :samples 4",
    },
    Topic {
        name: ":preview",
        aliases: &["preview"],
        summary: "choose how big the picture of `:render` is in the terminal",
        text: "\
:preview [fit|small|off]
  `small` (the default) shows renders in a third of the terminal, so the
  lines you just typed stay on screen above the picture; `fit` fills the
  terminal; `off` shows none (`:save` still writes files). A small render
  (`:size 40 30`) stays small. `:preview` alone shows the setting.
Example:
  :preview fit",
    },
    Topic {
        name: ":limits",
        aliases: &["limits", "max-calls", "max-primitives"],
        summary: "raise the limits on recursion and on primitives",
        text: "\
:limits [calls N] [primitives N]
  A procedure that calls itself forever, or a scene of billions of spheres,
  stops with an error instead of filling the memory. `calls` is the deepest
  chain of procedure calls (100000 unless changed), `primitives` the most
  spheres, planes and boxes a program may make (10000000). `:limits` alone
  shows them. From the command line: `--max-calls N`, `--max-primitives N`.
Example:
  :limits calls 500000",
    },
    Topic {
        name: ":load",
        aliases: &["load"],
        summary: "run a .ray file into the session",
        text: "\
:load FILE
  Runs every item of the file as if you had typed them, in any order. If the
  file has an error nothing of it is kept. `:undo` takes the whole file back;
  `:reload` runs it again after you change it.
Example:
  :load examples/balls.ray",
    },
    Topic {
        name: ":reload",
        aliases: &["reload"],
        summary: "run the file of the last :load again, as it is now",
        text: "\
:reload
  After you change the file you loaded last, runs its new version in place
  of the old one: what you typed after the :load stays and runs again on
  top of it, and nothing is counted twice. If the new version has an
  error, nothing changes. `:undo` takes a reload back.
Example:
  :load scenarios/hello.ray
  :reload",
    },
    Topic {
        name: ":watch",
        aliases: &["watch"],
        summary: "render a file again every time it is saved",
        text: "\
:watch FILE
  Loads FILE (in place of what it brought before, as :reload does) and
  renders it; then, every time an editor saves it, loads it again and
  renders the new picture, until Ctrl-C. A version with an error shows the
  error and leaves the last good picture. From the command line:
  `rayrepl FILE.ray --watch -o FILE.png`.
Example:
  :watch scenarios/hello.ray",
    },
    Topic {
        name: ":write",
        aliases: &["write"],
        summary: "write what the session holds as a .ray file",
        text: "\
:write FILE.ray
  Writes everything the session holds as a scene file, in the order a file
  needs: the last camera and ambient light, the lights, the last version of
  each procedure, then the instructions in the order they ran, each as you
  wrote it. `rayrepl FILE.ray` then renders the picture `:save` gives; the
  file's first lines say with which --width, --height, --depth, --samples
  and --time. When no file can give the same scene (a procedure redefined
  after it was used), it says why and writes nothing.
Example:
  :write my_scene.ray",
    },
    Topic {
        name: ":show",
        aliases: &["show"],
        summary: "print how a procedure, object or number was defined",
        text: "\
:show NAME
  Prints the last definition of NAME as it was written, with the comments
  around it, after a line saying where it came from: `<input 3>:1` is the
  third input, `scene.ray:12` line 12 of a loaded file.
Example:
  proc ring(n) put sphere center n, 0, 0 radius 0.3 kd 1 ks 0 phong 1 color 255, 120, 0 end end
  :show ring",
    },
    Topic {
        name: ":list",
        aliases: &["list"],
        summary: "list the inputs the session holds, in order",
        text: "\
:list
  Lists every input the session holds, in the order they run, each after
  the name messages give it (`<input 3>:1`); a loaded file shows as its
  `:load`. Inputs that failed or were taken back are not there.
Example:
  :list",
    },
    Topic {
        name: ":history",
        aliases: &["history"],
        summary: "list the lines you typed (this session and earlier ones)",
        text: "\
:history [N]
  Lists the last N lines typed in the editor (20 unless given), commands
  and mistakes included, from earlier sessions too. The up arrow brings
  them back.
Example:
  :history 50",
    },
    Topic {
        name: ":env",
        aliases: &["env"],
        summary: "list the names and procedures defined",
        text: "\
:env
  Lists the numbers and objects you named, and the procedures with their
  parameters.
Example:
  :env",
    },
    Topic {
        name: ":scene",
        aliases: &["scene"],
        summary: "show the camera, lights and what was put",
        text: "\
:scene
  Shows the camera, the ambient light, the lights and how many objects of
  each kind are in the scene, and the render settings.
Example:
  :scene",
    },
    Topic {
        name: ":undo",
        aliases: &["undo"],
        summary: "take back the last input that changed the session",
        text: "\
:undo
  Takes back the last input that was accepted (a whole :load counts as one,
  so does a :reset). Use it again to go further back.
Example:
  put sphere center 0, 0, 0 radius 9 kd 1 ks 0 phong 1 color 0, 0, 0 end
  :undo",
    },
    Topic {
        name: ":reset",
        aliases: &["reset"],
        summary: "start again from an empty session",
        text: "\
:reset
  Forgets everything you defined and put; the render settings stay.
  `:undo` brings it all back.
Example:
  :reset",
    },
    Topic {
        name: ":quit",
        aliases: &["quit", "exit", ":exit", ":q"],
        summary: "leave (Ctrl-D does too)",
        text: "\
:quit
  Leaves the session. Ctrl-D on an empty line does the same. If you typed
  inputs that no :write has written, it says so first: :quit (or Ctrl-D)
  again leaves without them.
Example:
  :quit",
    },
];

/// The page for `name` (a topic or one of its aliases, a word of the
/// language, or a word from elsewhere that means one), if there is one.
pub(crate) fn find(name: &str) -> Option<&'static Topic> {
    let topic = |wanted: &str| TOPICS.iter().find(|topic| topic.name == wanted || topic.aliases.contains(&wanted));
    topic(name).or_else(|| topic(word_topic(name)?)).or_else(|| {
        // `:help :sphere` or `:help help`: try with and without the colon.
        let other = match name.strip_prefix(':') {
            Some(bare) => bare.to_string(),
            None => format!(":{name}"),
        };
        TOPICS.iter().find(|topic| topic.name == other)
    })
}

/// The page the words table gives for `name`, or for the word of the
/// language that `name` means (`rayon` leads to the page of `radius`).
fn word_topic(name: &str) -> Option<&'static str> {
    let word = words::lookup(name)?;
    match word.kind {
        Kind::Elsewhere { means } => words::lookup(means).map(|meant| meant.topic),
        _ => Some(word.topic).filter(|topic| !topic.is_empty()),
    }
}

/// Every name `:help` knows, for completion and suggestions: the pages, and
/// the words of the language.
pub(crate) fn all_names() -> impl Iterator<Item = &'static str> {
    let pages = TOPICS.iter().flat_map(|topic| std::iter::once(topic.name).chain(topic.aliases.iter().copied()));
    pages.chain(words::language().map(|word| word.text))
}

/// The known name closest to a misspelt one.
pub(crate) fn suggestion(name: &str) -> Option<&'static str> {
    closest(name, all_names())
}

/// The overview: how to start, then every topic by group with its summary.
pub(crate) fn overview() -> String {
    let mut text = String::from(OVERVIEW);
    for (group, names) in GROUPS {
        text.push_str(&format!("\n  {group}:\n"));
        for name in *names {
            if let Some(topic) = find(name) {
                text.push_str(&format!("    {:<12} {}\n", topic.name, topic.summary));
            }
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::repl::commands::COMMANDS;

    #[test]
    fn every_word_of_the_language_has_a_page_with_an_example() {
        for word in words::language() {
            let topic = find(word.text).unwrap_or_else(|| panic!("no help for `{}`", word.text));
            assert!(topic.text.contains("Example"), "no example for `{}`", word.text);
        }
        for word in ["time", "conditions", "texture"] {
            assert!(find(word).is_some(), "no help for `{word}`");
        }
    }

    #[test]
    fn every_command_has_a_page_with_an_example() {
        for command in COMMANDS {
            let topic = find(command.name).unwrap_or_else(|| panic!("no help for `{}`", command.name));
            assert!(topic.text.contains("Example"), "no example for `{}`", command.name);
        }
    }

    #[test]
    fn every_page_is_in_the_overview() {
        let overview = overview();
        for topic in TOPICS {
            assert!(
                overview.contains(&format!("    {:<12} ", topic.name)),
                "`{}` missing from the overview",
                topic.name
            );
        }
    }

    /// The program text of a page's example (its command lines left out).
    fn example_program(topic: &Topic) -> String {
        let example = topic.text.split_once("Example").map_or("", |(_, rest)| rest);
        let lines = example.lines().skip(1).filter(|line| !line.trim_start().starts_with(':'));
        lines.collect::<Vec<_>>().join("\n")
    }

    #[test]
    fn every_example_is_valid_syntax() {
        use crate::lang::{SourceId, parse_items};
        for topic in TOPICS {
            let program = example_program(topic);
            if let Err(error) = parse_items(SourceId::default(), &program) {
                panic!("the example of `{}` does not parse: {}\n{program}", topic.name, error.message);
            }
        }
    }

    #[test]
    fn names_are_found_with_or_without_colon() {
        assert_eq!(find("render").map(|t| t.name), Some(":render"));
        assert_eq!(find(":render").map(|t| t.name), Some(":render"));
        assert_eq!(find("time").map(|t| t.name), Some("time"));
        assert_eq!(find(":time").map(|t| t.name), Some(":time"));
        assert_eq!(find("kd").map(|t| t.name), Some("texture"));
        assert_eq!(find("rayon").map(|t| t.name), Some("sphere"));
        assert_eq!(suggestion("spehre"), Some("sphere"));
    }
}
