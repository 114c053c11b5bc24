; Generated from the words table (src/lang/words.rs) by tools/generate/src/tree_sitter.rs:
; do not edit; cargo run -p generate -- write makes it again.
; The last pattern that matches a node gives its capture.

(identifier) @variable

(comment) @comment

(number) @number

[
  "camera"
  "distance"
  "angle"
  "ambient"
  "light"
  "vector"
  "rotation"
  "intensity"
  "let"
  "object"
  "put"
  "if"
  "print"
  "then"
  "else"
  "end"
  "center"
  "radius"
  "shift"
  "length"
  "kd"
  "ks"
  "phong"
  "color"
  "translate"
  "rotate"
  "scale"
  "group"
  "by"
] @keyword

[
  "proc"
] @keyword.function

[
  "sphere"
  "plane"
  "box"
] @type

[
  "sin"
  "cos"
  "sqrt"
] @function.builtin

[
  "pi"
] @constant.builtin

((identifier) @variable.builtin
  (#eq? @variable.builtin "time"))

(procedure
  name: (identifier) @function)

(call
  name: (identifier) @function)

(parameters
  (identifier) @variable.parameter)

[
  "+"
  "-"
  "*"
  "/"
  "="
  "!="
  "<"
  "<="
  ">"
  ">="
  "&"
  "|"
  "!"
] @operator

[
  ","
] @punctuation.delimiter

[
  "("
  ")"
] @punctuation.bracket

