

async def test_an_unsaved_yaml_file_reaches_the_models_that_load_it(client, ur):
    """ur10's visual meshes are named in config/ur10/visual_parameters.yaml (read with
    xacro.load_yaml in the sandboxed workers): pointing its base at a mesh that exists, in
    the unsaved buffer only, clears that finding in the macro file."""
    macro_uri = await linted(client, ur)
    yml = ur / "config" / "ur10" / "visual_parameters.yaml"
    text = yml.read_text()
    assert "package://ur_description/meshes/ur10/visual/base.dae" in text
    uri = open_doc(client, yml, text)
    edited = text.replace("meshes/ur10/visual/base.dae", "meshes/ur5e/visual/base.dae")
    change(client, uri, edited, 2)
    ds = await diagnostics_for(client, macro_uri, lambda ds: not any(
        "ur10/visual/base.dae" in d.message for d in ds))
    assert any("ur10/visual/shoulder.dae" in d.message for d in ds)   # the rest stays
    assert yml.read_text() == text


def test_a_buffer_outside_the_roots_is_never_read(tmp_path):
    """An include outside the package roots stays refused (UL902) even when the editor holds
    a buffer for that path: the overlay replaces a file's bytes only where the file itself
    could be read."""
    pytest.importorskip("pygls")
    from urdf_lint.lsp.state import Workspace
    pkg = tmp_path / "ws" / "bot"
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>bot</name></package>")
    outside = tmp_path / "outside.xacro"
    outside.write_text('<robot xmlns:xacro="http://wiki.ros.org/xacro"/>')
    model = pkg / "bot.xacro"
    model.write_text(f'<robot name="b" xmlns:xacro="http://wiki.ros.org/xacro">\n'
                     f'  <xacro:include filename="{outside}"/>\n  <link name="a"/>\n</robot>\n')
    ws = Workspace(str(pkg), pool_size=1)
    try:
        ws.buffers[str(outside)] = b'<robot xmlns:xacro="http://wiki.ros.org/xacro">' \
            b'<link name="from_the_buffer"/></robot>'
        ws.buffers[str(model)] = model.read_bytes()
        ws.lint()
        (f,) = [f for f in ws.findings if f.code == "UL902"]
        assert (f.file, f.line, f.col) == (str(model), 2, 3)
        rep = next(iter(r for r in ws.reports.values() if r.entry == str(model)))
        assert str(outside) not in rep.deps
    finally:
        ws.close()
