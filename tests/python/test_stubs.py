"""python/rrlab/_rrlab.pyi against the compiled module rrlab._rrlab: every
name of the module (functions, classes, their methods and properties) is in
the stub, of the same kind, with the same parameter names in the same order
and the same ones defaulted; and the stub names nothing the module lacks.
The module's signatures are pybind11's, the first line of each docstring
(`run(scenario: object, method: object = None, ...) -> dict`), or its
numbered lines for an overloaded function. Also: every public binding has a
docstring beyond its signature, and so has every public function and class
of the pure-Python modules."""
import ast
import os
import re
import types

import pytest

from rrlab import _rrlab

STUB = os.path.join(os.path.dirname(_rrlab.__file__), "_rrlab.pyi")


def split_top_level(text):
    """`a: X[b, c] = 1, d` -> ["a: X[b, c] = 1", "d"]: commas outside brackets and quotes."""
    parts, depth, quote, current = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(current)
            current = ""
            continue
        current += ch
    if current.strip():
        parts.append(current)
    return [part.strip() for part in parts]


def parameters(text):
    """[(name, has_default)] of a pybind11 parameter list."""
    out = []
    for part in split_top_level(text):
        name = re.match(r"[*]{0,2}\w+", part).group(0)
        out.append((name, " = " in part))  # pybind11 writes a default as `name: type = value`
    return out


def runtime_signatures(function, name, method):
    """The parameter lists of a pybind11 function from its docstring (self left out of a method's)."""
    doc = function.__doc__ or ""
    lines = doc.splitlines()
    if lines and lines[0].strip() == "Overloaded function.":
        heads = [line for line in lines if re.match(rf"\d+\. {re.escape(name)}\(", line)]
    else:
        heads = lines[:1]
    assert heads and all(head.lstrip("0123456789. ").startswith(name + "(") for head in heads), \
        f"{name}: no pybind11 signature in its docstring: {doc[:80]!r}"
    out = []
    for head in heads:
        inner = head[head.index("(") + 1:head.rindex(") ->")]
        found = parameters(inner)
        out.append(found[1:] if method else found)
    return sorted(out)


def stub_signature(node, method):
    args = node.args
    positional = args.posonlyargs + args.args
    defaults = [False] * (len(positional) - len(args.defaults)) + [True] * len(args.defaults)
    out = [(a.arg, d) for a, d in zip(positional, defaults)]
    if args.vararg:
        out.append(("*" + args.vararg.arg, False))
    out += [(a.arg, d is not None) for a, d in zip(args.kwonlyargs, args.kw_defaults)]
    if args.kwarg:
        out.append(("**" + args.kwarg.arg, False))
    return out[1:] if method else out


def is_property(node):
    return any(isinstance(d, ast.Name) and d.id == "property" for d in node.decorator_list)


def stub_members(body):
    """{name: ("property" | "function" | "class" | "value", [nodes])} of a module's or a class's body."""
    members = {}
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            kind = "property" if is_property(node) else "function"
            members.setdefault(node.name, (kind, []))[1].append(node)
        elif isinstance(node, ast.ClassDef):
            members[node.name] = ("class", [node])
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            members[node.target.id] = ("value", [node])
        elif isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    members[target.id] = ("alias", [node])
    return members


@pytest.fixture(scope="module")
def stub():
    with open(STUB, encoding="utf-8") as f:
        return stub_members(ast.parse(f.read(), STUB).body)


def module_names():
    return sorted(name for name in vars(_rrlab) if not name.startswith("__"))


def class_members(cls):
    """The names a class binds itself: public ones, and its constructor when it
    has one (a class without one has pybind11's __init__ that refuses, a slot
    wrapper, and no __init__ in the stub)."""
    return sorted(name for name in vars(cls) if not name.startswith("_") or
                  (name == "__init__" and not isinstance(vars(cls)[name], types.WrapperDescriptorType)))


def kind_of(value):
    if isinstance(value, type):
        return "class"
    if isinstance(value, property):
        return "property"
    if callable(value):
        return "function"
    return "value"


def test_the_stub_is_installed_beside_the_module_with_the_typed_marker():
    assert os.path.isfile(STUB)
    assert os.path.isfile(os.path.join(os.path.dirname(_rrlab.__file__), "py.typed"))


def test_the_stub_has_the_version(stub):
    assert stub["__version__"][0] == "value" and isinstance(_rrlab.__version__, str)


@pytest.mark.parametrize("name", module_names())
def test_each_name_of_the_module_is_in_the_stub_alike(stub, name):
    value = getattr(_rrlab, name)
    assert name in stub, f"rrlab._rrlab.{name} is missing from {STUB}"
    kind, nodes = stub[name]
    assert kind == kind_of(value), f"{name}: a {kind_of(value)} in the module, a {kind} in the stub"
    if kind == "function":
        assert sorted(stub_signature(n, False) for n in nodes) == runtime_signatures(value, name, False), name
    if kind == "class":
        members = stub_members(nodes[0].body)
        for member in class_members(value):
            attribute = vars(value)[member]
            where = f"{name}.{member}"
            assert member in members, f"rrlab._rrlab.{where} is missing from the stub"
            member_kind, member_nodes = members[member]
            assert member_kind == kind_of(attribute), \
                f"{where}: a {kind_of(attribute)} in the module, a {member_kind} in the stub"
            if member_kind == "function":
                assert sorted(stub_signature(n, True) for n in member_nodes) == \
                    runtime_signatures(getattr(value, member), member, True), where
        extra = [m for m, (k, _) in members.items() if k in ("function", "property") and m not in vars(value)]
        assert not extra, f"the stub's {name} has {extra}, which the module's has not"


def test_the_stub_names_nothing_the_module_lacks(stub):
    # private aliases and helper classes (TypedDicts) are the stub's own; a
    # private function (_run_sweep) must exist like the public names
    extra = [name for name, (kind, _) in stub.items()
             if not hasattr(_rrlab, name) and not (name.startswith("_") and kind in ("alias", "class"))]
    assert not extra, f"{STUB} names {extra}, which rrlab._rrlab has not"


def documented(doc, signature_first):
    """A docstring that says more than the signature pybind11 writes."""
    if not doc:
        return False
    text = doc.split("\n\n", 1)[1] if signature_first and "\n\n" in doc else ("" if signature_first else doc)
    return bool(text.strip())


@pytest.mark.parametrize("name", [n for n in module_names() if not n.startswith("_")])
def test_every_public_binding_has_a_docstring(name):
    value = getattr(_rrlab, name)
    if isinstance(value, type):
        assert documented(value.__doc__, False), name
        for member in class_members(value):
            attribute = vars(value)[member]
            if isinstance(attribute, property):
                assert documented(attribute.__doc__, False), f"{name}.{member}"
            else:
                assert documented(getattr(value, member).__doc__, True), f"{name}.{member}"
    elif callable(value):
        assert documented(value.__doc__, True), name


def test_every_public_function_and_class_of_the_pure_python_modules_has_a_docstring():
    import inspect

    import rrlab._sweep
    import rrlab.client
    import rrlab.errors
    import rrlab.method

    missing = []
    for module in (rrlab, rrlab._sweep, rrlab.client, rrlab.errors, rrlab.method):
        for name, value in vars(module).items():
            if name.startswith("_") or getattr(value, "__module__", None) != module.__name__:
                continue
            if inspect.isclass(value) or inspect.isfunction(value):
                if not (value.__doc__ or "").strip():
                    missing.append(f"{module.__name__}.{name}")
                members = vars(value).items() if inspect.isclass(value) else []
                missing += [f"{module.__name__}.{name}.{m}" for m, f in members
                            if not m.startswith("_") and inspect.isfunction(f) and not (f.__doc__ or "").strip()]
    assert not missing, missing
