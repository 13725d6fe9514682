"""The type stubs (metrosync/__init__.pyi) against the module: every public name is there, each
call with the parameters the module's own function has (names, order, defaults), so that an
editor completes what the module takes; and every public call has a docstring with an example."""
import ast
import inspect
import os

import metrosync

STUB = os.path.join(os.path.dirname(metrosync.__file__), "__init__.pyi")


def stub_tree():
    with open(STUB, encoding="utf-8") as f:
        return ast.parse(f.read())


def test_the_stubs_name_every_public_name():
    names = {node.name for node in stub_tree().body
             if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    assert set(metrosync.__all__) <= names, set(metrosync.__all__) - names


def test_the_stubs_give_each_call_its_parameters():
    functions = {n.name: n for n in stub_tree().body if isinstance(n, ast.FunctionDef)}
    for name, node in functions.items():
        real = inspect.signature(getattr(metrosync, name))
        args = node.args
        stub = [a.arg for a in args.posonlyargs + args.args]
        assert stub == [p.name for p in real.parameters.values()
                        if p.kind is not p.VAR_KEYWORD], name
        assert (args.kwarg is not None) == any(p.kind is p.VAR_KEYWORD
                                               for p in real.parameters.values()), name
        defaults = [ast.literal_eval(d) for d in args.defaults]
        real_defaults = [p.default for p in real.parameters.values()
                         if p.default is not inspect.Parameter.empty]
        assert defaults == real_defaults, name


def test_the_stubs_give_each_class_its_public_members():
    classes = {n.name: n for n in stub_tree().body if isinstance(n, ast.ClassDef)}
    for name, node in classes.items():
        if name in ("RigError", "SimulationError"):
            continue
        members = {getattr(b, "name", None) or getattr(getattr(b, "target", None), "id", None)
                   for b in node.body}
        real = {m for m in vars(getattr(metrosync, name)) if not m.startswith("_")}
        assert real <= members, (name, real - members)


def test_every_public_call_has_a_docstring_with_an_example():
    for name in metrosync.__all__:
        obj = getattr(metrosync, name)
        if name in ("RigError",):
            continue
        doc = inspect.getdoc(obj) or ""
        assert len(doc) > 40, name
        if inspect.isfunction(obj) or name.endswith("Result") or name == "Rig":
            assert ">>> " in doc, name
