"""The Jupyter project's own conformance suite, jupyter_kernel_test, for
the features the kernel has: kernel info, execute with stdout and stderr,
display data, errors, completion, is_complete, inspect, the iopub welcome.
Its history and execute_result tests need a cell whose value is an
`execute_result`; cells of the language print and show pictures (stream
and display_data) and have no value, so they skip, and test_kernel.py
checks history with the client itself."""

import unittest

import jupyter_kernel_test


class RayreplKernelTests(jupyter_kernel_test.KernelTests):
    kernel_name = "rayrepl"
    language_name = "ray"
    file_extension = ".ray"

    # The language has no strings: `:show` prints a procedure's text, its
    # comment included, after the confirmation of its definition (one
    # stream message, as the kernel gathers the lines of a cell).
    code_hello_world = "proc greet()\n  # hello, world\nend\n:show greet"
    # A warning goes to stderr: a colour over 255 is clamped.
    code_stderr = "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 300, 0, 0 end"
    code_generate_error = "put box end"
    code_display_data = [
        {
            "code": ":size 8 6\nlight vector 0, 0, 1 intensity 1 end\n:render",
            "mime": "image/png",
        },
    ]
    completion_samples = [
        {"text": "put sph", "matches": {"sphere "}},
        {"text": ":ren", "matches": {":render "}},
    ]
    complete_code_samples = ["put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 1, 2, 3 end", ":render", ""]
    incomplete_code_samples = ["proc p(n)", "put sphere center 0, 0, 0", "if 1 < 2 then"]
    invalid_code_samples = ["put sphere center 0, 0, 0 radius 1 radius 2 end )", "let = 3"]
    code_inspect_sample = "sphere"
    support_iopub_welcome = True


class RayreplWelcomeTests(jupyter_kernel_test.IopubWelcomeTests):
    kernel_name = "rayrepl"
    support_iopub_welcome = True


if __name__ == "__main__":
    unittest.main()
