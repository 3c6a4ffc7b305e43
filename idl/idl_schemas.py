#!/usr/bin/env python3
"""Writes the MCAP `omgidl` schema data of every struct of an IDL file as a C++ source.

    idl_schemas.py IN.idl OUT.cpp

A type's schema text is the IDL it needs to be read on its own: its struct and every struct,
enum and typedef it uses (transitively), in the file's order (a definition always comes before
its use), each inside the modules it was declared in; comments dropped. OUT.cpp defines
robodds::idl_schema_text() (idl/idl_schema.hpp). Run at build time by idl/CMakeLists.txt.

The IDL subset read is that of idl/robodds.idl: nested `module`s holding `struct`, `enum` and
`typedef` definitions with annotations (@final, @key); anything else is an error naming the file
and line, so a new construct cannot be dropped from the schemas silently.
"""
import re
import sys

KEYWORDS = {
    "module", "struct", "enum", "typedef", "sequence", "string", "wstring", "unsigned", "long", "short",
    "double", "float", "boolean", "char", "wchar", "octet", "int8", "uint8", "int16", "uint16", "int32",
    "uint32", "int64", "uint64", "key", "final", "appendable", "mutable", "const",
}


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


class Definition:
    def __init__(self, kind, name, modules, text):
        self.kind, self.name, self.modules, self.text = kind, name, modules, text
        self.qualified = "::".join(modules + [name])


def parse(path, text):
    """The definitions of `text` in order, each with its module path and text."""
    text = strip_comments(text)
    defs = []
    modules = []
    pos = 0
    token = re.compile(
        r"\s*(?:(?P<module>module\s+(?P<mname>\w+)\s*\{)"
        r"|(?P<close>\}\s*;)"
        r"|(?P<def>(?:@\w+(?:\([^)]*\))?\s*)*(?P<kind>struct|enum)\s+(?P<name>\w+)\s*\{[^{}]*\}\s*;)"
        r"|(?P<typedef>typedef\s+[^;]*?\s(?P<tname>\w+)\s*(?:\[[^\]]*\]\s*)*;))",
        re.S)
    while pos < len(text):
        if not text[pos:].strip():
            break
        m = token.match(text, pos)
        if m is None:
            rest = text[pos:].lstrip()
            line = text.count("\n", 0, len(text) - len(rest)) + 1
            sys.exit("error: %s:%d: not understood by the schema generator (idl/idl_schemas.py): %s"
                     % (path, line, rest.splitlines()[0]))
        if m.group("module"):
            modules.append(m.group("mname"))
        elif m.group("close"):
            if not modules:
                sys.exit("error: %s: unbalanced '};'" % path)
            modules.pop()
        elif m.group("def"):
            defs.append(Definition(m.group("kind"), m.group("name"), list(modules), normalise(m.group("def"))))
        else:
            defs.append(Definition("typedef", m.group("tname"), list(modules), normalise(m.group("typedef"))))
        pos = m.end()
    if modules:
        sys.exit("error: %s: module %s not closed" % (path, "::".join(modules)))
    return defs


def normalise(text):
    """The definition's lines without trailing blanks or blank lines."""
    return "\n".join(line.rstrip() for line in text.strip().splitlines() if line.strip())


def references(defn, by_name):
    """Definitions `defn` uses: identifiers naming one, resolved from its module outwards."""
    if defn.kind == "enum":
        return []
    found = []
    body = defn.text[defn.text.index("{"):] if defn.kind == "struct" else defn.text
    for ident in re.findall(r"[A-Za-z_][\w]*(?:::[A-Za-z_]\w*)*", body):
        if ident in KEYWORDS or ident == defn.name:
            continue
        for depth in range(len(defn.modules), -1, -1):
            candidate = "::".join(defn.modules[:depth] + [ident])
            if candidate in by_name:
                found.append(by_name[candidate])
                break
    return found


def schema_text(root, defs, by_name):
    needed = set()
    stack = [root]
    while stack:
        d = stack.pop()
        if d.qualified in needed:
            continue
        needed.add(d.qualified)
        stack.extend(references(d, by_name))
    out = []
    open_modules = []
    for d in defs:
        if d.qualified not in needed:
            continue
        common = 0
        while common < min(len(open_modules), len(d.modules)) and open_modules[common] == d.modules[common]:
            common += 1
        while len(open_modules) > common:
            open_modules.pop()
            out.append("  " * len(open_modules) + "};")
        while len(open_modules) < len(d.modules):
            out.append("  " * len(open_modules) + "module %s {" % d.modules[len(open_modules)])
            open_modules.append(d.modules[len(open_modules)])
        indent = "  " * len(open_modules)
        out.extend(indent + line.strip() if i == 0 or line.strip().startswith("}") else indent + "  " + line.strip()
                   for i, line in enumerate(d.text.splitlines()))
    while open_modules:
        open_modules.pop()
        out.append("  " * len(open_modules) + "};")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: idl_schemas.py IN.idl OUT.cpp")
    path, out_path = sys.argv[1], sys.argv[2]
    with open(path, encoding="utf-8") as f:
        defs = parse(path, f.read())
    by_name = {d.qualified: d for d in defs}
    entries = []
    for d in defs:
        if d.kind != "struct":
            continue
        text = schema_text(d, defs, by_name)
        if ')idl"' in text:
            sys.exit("error: %s: struct %s: its text would end the C++ raw string" % (path, d.qualified))
        entries.append('      {"%s", R"idl(%s)idl"},' % (d.qualified, text))
    source = """// Generated by idl/idl_schemas.py from %s at build time: do not edit.
#include "idl/idl_schema.hpp"

#include <map>

namespace robodds {

std::string idl_schema_text(const std::string& type_name) {
  static const std::map<std::string, std::string> kSchemas = {
%s
  };
  auto it = kSchemas.find(type_name);
  return it == kSchemas.end() ? std::string() : it->second;
}

}  // namespace robodds
""" % (path.split("/")[-1], "\n".join(entries))
    with open(out_path, "w", encoding="utf-8") as f:
        f.write(source)


if __name__ == "__main__":
    main()
