"""Every bad input gets one clear line on stderr, a non-zero exit, and no output file."""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from cbc3d_testing import write_nifti  # noqa: E402

CLI = os.environ["CBC3D_CLI"]
SOURCE = os.environ["CBC3D_SOURCE_DIR"]
PHANTOM = os.path.join(SOURCE, "Data", "ball.vti")
failures = []


def expect_error(name, args, fragment, workdir):
    out = os.path.join(workdir, name + ".vtu")
    result = subprocess.run([CLI] + [a.replace("OUT", out) for a in args], capture_output=True,
                            text=True, timeout=120)
    lines = [l for l in result.stderr.splitlines() if l.strip()]
    problems = []
    if result.returncode == 0:
        problems.append("exit code 0")
    if len(lines) != 1 or not lines[0].startswith("cbc3d: error: "):
        problems.append("stderr is not one 'cbc3d: error:' line: %r" % result.stderr)
    elif fragment.lower() not in lines[0].lower():
        problems.append("message %r does not mention %r" % (lines[0], fragment))
    leftovers = [f for f in os.listdir(workdir) if f.startswith(name + ".vtu")]
    if leftovers:
        problems.append("files left behind: %s" % leftovers)
    if result.stdout:
        problems.append("stdout not empty: %r" % result.stdout)
    status = "ok  " if not problems else "FAIL"
    print("%s %-22s -> %s" % (status, name, lines[0] if lines else result.stderr))
    if problems:
        failures.append((name, problems))
        for p in problems:
            print("     ", p)


with tempfile.TemporaryDirectory() as work:
    def image(name, dims, values, dtype="int16"):
        path = os.path.join(work, name)
        write_nifti(path, dims, values, dtype)
        return path

    n = 8 * 8 * 8
    ball = [1 if (i % 8 - 3.5) ** 2 + (i // 8 % 8 - 3.5) ** 2 + (i // 64 - 3.5) ** 2 < 9 else 0 for i in range(n)]
    empty = image("empty.nii", (8, 8, 8), [0] * n)
    flat = image("flat.nii.gz", (8, 8, 1), [1] * 64)
    fraction = image("fraction.nii", (8, 8, 8), [v * 1.5 for v in ball], "float32")
    rgb = image("rgb.nii", (8, 8, 8), [(v, v, v) for v in ball], "rgb24")
    garbage = os.path.join(work, "garbage.nii.gz")
    with open(garbage, "wb") as f:
        f.write(b"this is not an image" * 50)
    garbage_vti = os.path.join(work, "garbage.vti")
    with open(garbage_vti, "w") as f:
        f.write("<VTKFile type='ImageData'><broken")
    folder = os.path.join(work, "folder.nii")
    os.mkdir(folder)
    png = os.path.join(work, "picture.png")
    with open(png, "wb") as f:
        f.write(b"\x89PNG")
    blocked = os.path.join(work, "blocked")
    os.makedirs(os.path.join(blocked, "m.h5"))  # a folder where the .xdmf's .h5 would go

    cases = [
        ("missing", [os.path.join(work, "nothere.nii.gz"), "-o", "OUT"], "No such file"),
        ("directory", [folder, "-o", "OUT"], "directory"),
        ("unknown_extension", [png, "-o", "OUT"], "unknown image extension"),
        ("garbage_nifti", [garbage, "-o", "OUT"], "cannot read"),
        ("garbage_vti", [garbage_vti, "-o", "OUT"], "cannot read"),
        ("no_tissue", [empty, "-o", "OUT"], "no tissue"),
        ("two_d", [flat, "-o", "OUT"], "3-D"),
        ("non_integral", [fraction, "-o", "OUT"], "non-integral"),
        ("multi_component", [rgb, "-o", "OUT"], "components"),
        ("zero_bcc_size", [PHANTOM, "-o", "OUT", "--bcc-size", "0"], "--bcc-size"),
        ("negative_bcc_size", [PHANTOM, "-o", "OUT", "--bcc-size", "-3"], "--bcc-size"),
        ("text_bcc_size", [PHANTOM, "-o", "OUT", "--bcc-size", "big"], "--bcc-size"),
        ("tiny_bcc_size", [PHANTOM, "-o", "OUT", "--bcc-size", "0.00001"], "memory"),
        ("fidelity_range", [PHANTOM, "-o", "OUT", "--fidelity", "1.5"], "--fidelity"),
        ("max_edge_negative", [PHANTOM, "-o", "OUT", "--max-edge", "-2"], "--max-edge"),
        ("max_edge_zero", [PHANTOM, "-o", "OUT", "--max-edge", "0"], "--max-edge"),
        ("max_edge_nan", [PHANTOM, "-o", "OUT", "--max-edge", "nan"], "--max-edge"),
        ("max_edge_label_zero", [PHANTOM, "-o", "OUT", "--max-edge", "1=0"], "--max-edge"),
        ("max_edge_unknown_label", [PHANTOM, "-o", "OUT", "--max-edge", "9=4"], "tissue 9"),
        ("max_edge_background", [PHANTOM, "-o", "OUT", "--max-edge", "0=4"], "background"),
        ("max_edge_below_floor", [PHANTOM, "-o", "OUT", "--min-edge", "1", "--max-edge", "0.5"], "minimum edge"),
        ("max_tets_zero", [PHANTOM, "-o", "OUT", "--max-tets", "0"], "--max-tets"),
        ("max_tets_negative", [PHANTOM, "-o", "OUT", "--max-tets", "-5"], "--max-tets"),
        ("max_tets_fraction", [PHANTOM, "-o", "OUT", "--max-tets", "1.5"], "--max-tets"),
        ("max_tets_text", [PHANTOM, "-o", "OUT", "--max-tets", "many"], "--max-tets"),
        ("min_edge_negative", [PHANTOM, "-o", "OUT", "--min-edge", "-1"], "--min-edge"),
        ("min_edge_nan", [PHANTOM, "-o", "OUT", "--min-edge", "nan"], "--min-edge"),
        ("fidelity_label_range", [PHANTOM, "-o", "OUT", "--fidelity", "1=1.5"], "--fidelity"),
        ("fidelity_unknown_label", [PHANTOM, "-o", "OUT", "--fidelity", "9=0.9"], "tissue 9"),
        ("boundary_distance_text", [PHANTOM, "-o", "OUT", "--boundary-distance", "far"], "--boundary-distance"),
        ("bad_pattern", [PHANTOM, "-o", "OUT", "--pattern", "diagonal"], "--pattern"),
        ("bad_targets", [PHANTOM, "-o", "OUT", "--targets", "middle"], "--targets"),
        ("bad_keep_volumes", [PHANTOM, "-o", "OUT", "--keep-volumes", "yes"], "--keep-volumes"),
        ("negative_iterations", [PHANTOM, "-o", "OUT", "--iterations", "-1"], "--iterations"),
        ("bad_threads", [PHANTOM, "-o", "OUT", "--threads", "two"], "--threads"),
        ("unknown_option", [PHANTOM, "-o", "OUT", "--smooth"], "unknown option"),
        ("no_output", [PHANTOM], "no output"),
        ("bad_output_extension", [PHANTOM, "-o", "OUT.stl"], "output extension"),
        ("bad_second_output", [PHANTOM, "-o", "OUT", "-o", "OUT.stl"], "output extension"),
        ("bad_surfaces_extension", [PHANTOM, "-o", "OUT", "--surfaces", "OUT.ply"], "surfaces extension"),
        ("bad_msh_version", [PHANTOM, "-o", "OUT.msh", "--msh-version", "3"], "--msh-version"),
        ("output_twice", [PHANTOM, "-o", "OUT.msh", "-o", "OUT.msh"], "twice"),
        ("surfaces_folder_missing", [PHANTOM, "-o", "OUT", "--surfaces", os.path.join(work, "no", "s.vtp")],
         "cannot write"),
        ("no_tissue_every_format", [empty, "-o", "OUT", "-o", "OUT.msh", "-o", "OUT.inp", "-o", "OUT.mesh",
                                    "-o", "OUT.feb", "-o", "OUT.xdmf", "-o", "OUT.exo", "--surfaces", "OUT.vtp"],
         "no tissue"),
        ("missing_value", [PHANTOM, "-o", "OUT", "--bcc-size"], "needs a value"),
        ("output_folder_missing", [PHANTOM, "-o", os.path.join(work, "no", "dir", "m.vtu")], "cannot write"),
        ("background_everything", [PHANTOM, "-o", "OUT", "--background", "0", "--background", "1"], "no tissue"),
        # .xdmf is two files (the .xdmf and its .h5): neither appears when the folder is missing
        ("xdmf_folder_missing", [PHANTOM, "-o", os.path.join(work, "no", "dir", "m.xdmf")], "cannot write"),
        # ... nor when the .h5's name is taken by a folder (checked below: nothing else there)
        ("xdmf_h5_blocked", [PHANTOM, "-o", os.path.join(blocked, "m.xdmf")], "m.h5"),
    ]
    for name, args, fragment in cases:
        expect_error(name, args, fragment, work)
    if sorted(os.listdir(blocked)) != ["m.h5"]:
        failures.append(("xdmf_h5_blocked", sorted(os.listdir(blocked))))
        print("FAIL xdmf_h5_blocked left:", sorted(os.listdir(blocked)))
    stray = [f for f in os.listdir(work) if ".part-" in f]
    if stray:
        failures.append(("temporary files", stray))
        print("FAIL temporary files left:", stray)

print("%d passed, %d failed" % (len(cases) - len(failures), len(failures)))
sys.exit(1 if failures else 0)
