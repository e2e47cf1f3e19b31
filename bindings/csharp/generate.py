#!/usr/bin/env python3
"""Generate the C# binding of the whole C API from include/cloth/cloth.h.

    bindings/csharp/generate.py [--header PATH] --out FILE [--properties FILE] [--c-layouts FILE]

Writes one C# file (namespace ClothSharp): every constant macro, enum,
struct, callback type and function of the header, plus null ids and id
equality from the header-only definitions. With --properties, also the
owners' get/set properties (ClothSharp.g.cs, which the hand-written
ClothSharp.cs needs): one per cloth_get_X / cloth_set_X pair of one shape.
Python 3 standard library only.

The generator knows the header's grammar (a small, regular subset of C99)
and nothing else: a declaration it cannot bind exactly (an unknown type, a
bool or array of structs in a struct, a macro that is not a number, an
inline function other than an id equality, ...) stops it with a message and
exit status 1, so the binding cannot silently drift from the header.

Mapping (bindings/csharp/README.md explains the choices):
  - types: cloth_world_desc -> ClothWorldDesc (PascalCase of the C name),
    fields PascalCase (max_cloths -> MaxCloths), enumerators PascalCase
    without their enum's common prefix (CLOTH_ERROR_NULL_POINTER ->
    ClothResult.ErrorNullPointer); functions and constants keep their C
    names (Native.cloth_step, Native.CLOTH_MAX_WORLDS).
  - structs are blittable, LayoutKind.Sequential: pointer and function
    pointer fields are IntPtr, float[3] and float[4] are Float3 and Float4,
    other arrays are fixed buffers with Get/Set accessors.
  - every function is a DllImport with CallingConvention.Cdecl and
    ExactSpelling. A function with pointer parameters has two: one with raw
    pointers (T*, may pass null) and one with ref/out (no unsafe code at
    the call site; const T* is [In] ref T, since Mono passes a P/Invoke
    `in` argument by value). void* and function pointers are IntPtr.
  - bool (C99 _Bool, one byte) is byte in every signature; const char*
    returns are IntPtr, with a companion *_str() that copies the UTF-8
    string; const char* parameters also get a string overload (UTF-8).
  - callback types are delegates with UnmanagedFunctionPointer(Cdecl).
"""

import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_HEADER = os.path.join(HERE, "..", "..", "include", "cloth", "cloth.h")

PRIMITIVES = {
    "uint8_t": "byte",
    "int8_t": "sbyte",
    "uint16_t": "ushort",
    "int16_t": "short",
    "uint32_t": "uint",
    "int32_t": "int",
    "uint64_t": "ulong",
    "int64_t": "long",
    "float": "float",
    "double": "double",
    "size_t": "UIntPtr",
}
# Macros that are part of the header's machinery, not constants.
MACHINERY_MACROS = {"CLOTH_CLOTH_H", "CLOTH_API", "CLOTH_CALL"}
CSHARP_KEYWORDS = set(
    """abstract as base bool break byte case catch char checked class const continue decimal default
    delegate do double else enum event explicit extern false finally fixed float for foreach goto if
    implicit in int interface internal is lock long namespace new null object operator out override
    params private protected public readonly ref return sbyte sealed short sizeof stackalloc static
    string struct switch this throw true try typeof uint ulong unchecked unsafe ushort using virtual
    void volatile while""".split()
)


class BindError(Exception):
    pass


def fail(line, message):
    raise BindError("cloth.h:%d: cannot bind: %s" % (line, message))


# ---------------------------------------------------------------- tokens


class Tok:
    def __init__(self, kind, text, line):
        self.kind = kind  # "id", "num", "punct", "str", "doc", "pp"
        self.text = text
        self.line = line

    def __repr__(self):
        return "%s:%r@%d" % (self.kind, self.text, self.line)


TOKEN_RE = re.compile(
    r"""(?P<doc>///(?!<)[^\n]*)
      | (?P<docafter>///<[^\n]*)
      | (?P<comment>//[^\n]*)
      | (?P<block>/\*.*?\*/)
      | (?P<str>"(?:[^"\\\n]|\\.)*")
      | (?P<num>(?:0[xX][0-9A-Fa-f]+|[0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?)[uUlLfF]*)
      | (?P<id>[A-Za-z_][A-Za-z0-9_]*)
      | (?P<punct>==|&&|[{}()\[\];,=*.&-])
      | (?P<space>[ \t\r\n]+)
    """,
    re.S | re.X,
)


PP_START_RE = re.compile(r"[ \t]*#")


def tokenize(text):
    tokens = []
    line = 1
    pos = 0
    at_line_start = True
    while pos < len(text):
        if at_line_start:
            m = PP_START_RE.match(text, pos)
            if m:
                # A preprocessor line, with its continuations.
                end = pos
                while True:
                    nl = text.find("\n", end)
                    if nl < 0:
                        nl = len(text)
                    if text[nl - 1 : nl] == "\\":
                        end = nl + 1
                        continue
                    break
                raw = text[pos:nl].replace("\\\n", " ")
                raw = re.sub(r"/\*.*?\*/", " ", raw)
                raw = re.sub(r"//.*", "", raw)
                tokens.append(Tok("pp", raw.strip(), line))
                line += text[pos:nl].count("\n")
                pos = nl
                continue
        m = TOKEN_RE.match(text, pos)
        if not m:
            fail(line, "unexpected character %r" % text[pos])
        kind = m.lastgroup
        value = m.group(kind)
        if kind == "doc":
            body = value[3:]
            tokens.append(Tok("doc", body[1:] if body.startswith(" ") else body, line))
        elif kind == "docafter":
            fail(line, "a trailing ///< comment (the generator reads docs before a declaration)")
        elif kind in ("num", "id", "punct", "str"):
            tokens.append(Tok(kind, value, line))
        newlines = value.count("\n")
        line += newlines
        if newlines:
            at_line_start = True
        elif kind != "space":
            at_line_start = False
        pos = m.end()
    return tokens


# ---------------------------------------------------------------- model


class CType:
    """A C type as the header spells it: [const] base [*]."""

    def __init__(self, base, const=False, pointers=0):
        self.base = base
        self.const = const
        self.pointers = pointers

    def __repr__(self):
        return ("const " if self.const else "") + self.base + "*" * self.pointers


class Decl:
    def __init__(self, name, ctype, array, docs, line):
        self.name = name
        self.ctype = ctype
        self.array = array  # None, or the element count as written (literal or macro)
        self.docs = docs
        self.line = line


class Header:
    def __init__(self):
        self.constants = []  # (name, C# type, C# literal, docs, line)
        self.enums = []  # (name, [(member, value, docs, line)], docs, line)
        self.structs = []  # (name, [Decl], docs, line)
        self.callbacks = []  # (name, return CType, [Decl], docs, line)
        self.functions = []  # (name, return CType, [Decl], docs, line)
        self.null_ids = []  # (name, type, line)
        self.equalities = []  # (name, type, line)


class Parser:
    def __init__(self, tokens):
        self.toks = tokens
        self.i = 0
        self.h = Header()

    # -- helpers
    def peek(self, k=0):
        j = self.i + k
        return self.toks[j] if j < len(self.toks) else None

    def next(self):
        t = self.peek()
        if t is None:
            raise BindError("cloth.h: unexpected end of file")
        self.i += 1
        return t

    def expect(self, text):
        t = self.next()
        if t.text != text:
            fail(t.line, "expected %r, found %r" % (text, t.text))
        return t

    def ident(self):
        t = self.next()
        if t.kind != "id":
            fail(t.line, "expected a name, found %r" % t.text)
        return t

    def docs(self):
        out = []
        while self.peek() is not None and self.peek().kind == "doc":
            out.append(self.next().text)
        return out

    def ctype(self):
        t = self.peek()
        const = False
        if t.text == "const":
            const = True
            self.next()
        base = self.ident()
        if base.text in ("struct", "enum", "union", "unsigned", "signed", "long", "short", "int"):
            fail(base.line, "type %r (the header uses fixed-width types and typedef names only)" % base.text)
        if self.peek().text == "const":
            fail(base.line, "a const after the type name")
        pointers = 0
        while self.peek().text == "*":
            self.next()
            pointers += 1
            if self.peek().text == "const":
                fail(base.line, "a const pointer")
        if pointers > 1:
            fail(base.line, "a pointer to a pointer")
        return CType(base.text, const, pointers)

    def declarator(self, docs):
        line = self.peek().line
        ctype = self.ctype()
        name = self.ident().text
        array = None
        if self.peek().text == "[":
            self.next()
            size = self.next()
            if size.kind not in ("num", "id"):
                fail(size.line, "array size %r" % size.text)
            array = size.text
            self.expect("]")
            if self.peek().text == "[":
                fail(line, "a multi-dimensional array")
        return Decl(name, ctype, array, docs, line)

    def params(self):
        self.expect("(")
        out = []
        if self.peek().text == "void" and self.peek(1).text == ")":
            self.next()
            self.next()
            return out
        while True:
            out.append(self.declarator([]))
            t = self.next()
            if t.text == ")":
                return out
            if t.text != ",":
                fail(t.line, "expected ',' or ')' in a parameter list, found %r" % t.text)

    # -- top level
    def parse(self):
        extern_c_open = 0
        while self.peek() is not None:
            docs = self.docs()
            t = self.peek()
            if t is None:
                break
            if t.kind == "pp":
                self.next()
                self.preprocessor(t, docs)
            elif t.text == "extern" and self.peek(1).kind == "str":
                self.next()
                self.next()
                self.expect("{")
                extern_c_open += 1
            elif t.text == "}" and extern_c_open:
                self.next()
                extern_c_open -= 1
            elif t.text == "typedef":
                self.typedef(docs)
            elif t.text == "CLOTH_API":
                self.function(docs)
            elif t.text == "static":
                self.static(docs)
            else:
                fail(t.line, "an unexpected declaration starting with %r" % t.text)
        return self.h

    def preprocessor(self, t, docs):
        m = re.match(r"#\s*define\s+(\w+)(\(.*?\))?\s*(.*)$", t.text)
        if not m:
            return  # #if, #ifdef, #else, #endif, #include, #ifndef, #error
        name, args, value = m.group(1), m.group(2), m.group(3).strip()
        if name in MACHINERY_MACROS:
            return
        if args:
            fail(t.line, "function-like macro %s" % name)
        if not name.startswith("CLOTH_"):
            fail(t.line, "macro %s outside the CLOTH_ namespace" % name)
        number = re.fullmatch(r"(-?)([0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?)([uUfF]?)", value)
        hexnum = re.fullmatch(r"0[xX]([0-9A-Fa-f]+)([uU]?)", value)
        if hexnum:
            v = int(hexnum.group(1), 16)
            ctype = "uint" if hexnum.group(2) else "int"
            literal = value.rstrip("uU") + ("u" if ctype == "uint" else "")
        elif number:
            sign, digits, suffix = number.groups()
            if suffix in ("f", "F"):
                ctype, literal = "float", sign + digits + "f"
            elif "." in digits or "e" in digits.lower():
                ctype, literal = "double", sign + digits
            else:
                v = int(sign + digits)
                ctype = "uint" if suffix else "int"
                limit = 2**32 if ctype == "uint" else 2**31
                if not (-limit <= v < limit):
                    fail(t.line, "macro %s = %s does not fit 32 bits" % (name, value))
                literal = sign + digits + ("u" if suffix else "")
        else:
            fail(t.line, "macro %s is not a number (%r)" % (name, value))
        self.h.constants.append((name, ctype, literal, docs, t.line))

    def typedef(self, docs):
        start = self.expect("typedef")
        t = self.peek()
        if t.text == "struct":
            self.next()
            tag = self.ident().text
            self.expect("{")
            fields = []
            while self.peek().text != "}":
                fdocs = self.docs()
                field = self.declarator(fdocs)
                self.expect(";")
                fields.append(field)
            self.expect("}")
            name = self.ident().text
            self.expect(";")
            if tag != name:
                fail(start.line, "struct tag %s differs from its typedef %s" % (tag, name))
            self.h.structs.append((name, fields, docs, start.line))
        elif t.text == "enum":
            self.next()
            tag = self.ident().text
            self.expect("{")
            members = []
            while self.peek().text != "}":
                mdocs = self.docs()
                member = self.ident()
                if self.peek().text != "=":
                    fail(member.line, "enumerator %s without an explicit value" % member.text)
                self.next()
                negative = False
                if self.peek().text == "-":
                    self.next()
                    negative = True
                value = self.next()
                if value.kind != "num" or not re.fullmatch(r"(0[xX][0-9A-Fa-f]+|[0-9]+)", value.text):
                    fail(value.line, "enumerator %s = %r is not an integer literal" % (member.text, value.text))
                v = int(value.text, 0) * (-1 if negative else 1)
                if not (-(2**31) <= v < 2**31):
                    fail(value.line, "enumerator %s does not fit an int" % member.text)
                members.append((member.text, v, mdocs, member.line))
                if self.peek().text == ",":
                    self.next()
            self.expect("}")
            name = self.ident().text
            self.expect(";")
            if tag != name:
                fail(start.line, "enum tag %s differs from its typedef %s" % (tag, name))
            self.h.enums.append((name, members, docs, start.line))
        else:
            ret = self.ctype()
            if self.peek().text != "CLOTH_CALL":
                fail(start.line, "a function type without CLOTH_CALL (its calling convention)")
            self.next()
            name = self.ident().text
            if not name.endswith("_fn"):
                fail(start.line, "typedef %s: only struct, enum and callback (*_fn) typedefs" % name)
            params = self.params()
            self.expect(";")
            self.h.callbacks.append((name, ret, params, docs, start.line))

    def function(self, docs):
        start = self.expect("CLOTH_API")
        ret = self.ctype()
        if self.peek().text != "CLOTH_CALL":
            fail(start.line, "a function without CLOTH_CALL (its calling convention)")
        self.next()
        name = self.ident().text
        params = self.params()
        self.expect(";")
        self.h.functions.append((name, ret, params, docs, start.line))

    def static(self, docs):
        start = self.expect("static")
        if self.peek().text == "const":
            self.next()
            type_name = self.ident().text
            name = self.ident().text
            self.expect("=")
            self.expect("{")
            values = []
            while self.peek().text != "}":
                v = self.next()
                if v.text == ",":
                    continue
                values.append(v.text)
            self.expect("}")
            self.expect(";")
            if any(v != "0" for v in values):
                fail(start.line, "static constant %s is not all-zero (only null ids are bound)" % name)
            self.h.null_ids.append((name, type_name, len(values), start.line))
        elif self.peek().text == "inline":
            self.next()
            ret = self.ctype()
            name = self.ident().text
            params = self.params()
            self.expect("{")
            body = []
            depth = 1
            while True:
                t = self.next()
                if t.text == "{":
                    depth += 1
                elif t.text == "}":
                    depth -= 1
                    if depth == 0:
                        break
                body.append(t.text)
            if (
                ret.base != "bool"
                or ret.pointers
                or len(params) != 2
                or params[0].ctype.base != params[1].ctype.base
                or params[0].ctype.pointers
                or not name.endswith("_equal")
            ):
                fail(start.line, "inline function %s (only id equalities, bool f(T a, T b), are bound)" % name)
            self.h.equalities.append((name, params[0].ctype.base, params[0].name, params[1].name, body, start.line))
        else:
            fail(start.line, "a static declaration that is neither a null id nor an inline id equality")


# ---------------------------------------------------------------- C# emission


def pascal(name):
    return "".join(part[:1].upper() + part[1:] for part in name.split("_") if part)


def pascal_upper(name):
    return "".join(part[:1] + part[1:].lower() for part in name.split("_") if part)


def xml(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def doc_lines(docs, indent):
    if not docs:
        return []
    out = [indent + "/// <summary>"]
    out += [indent + "/// " + xml(d) if d else indent + "///" for d in docs]
    out.append(indent + "/// </summary>")
    return out


def param_name(name):
    return "@" + name if name in CSHARP_KEYWORDS else name


class Emitter:
    def __init__(self, header):
        self.h = header
        self.enum_names = {e[0]: pascal(e[0]) for e in header.enums}
        self.struct_names = {s[0]: pascal(s[0]) for s in header.structs}
        self.struct_fields = {s[0]: s[1] for s in header.structs}
        self.callback_names = {c[0]: pascal(c[0]) for c in header.callbacks}
        self.constants = {c[0]: c for c in header.constants}
        self.out = []

    def w(self, line=""):
        self.out.append(line)

    def versioned(self, struct):
        fields = self.struct_fields.get(struct)
        return bool(fields) and fields[0].name == "struct_size" and fields[0].ctype.base == "uint32_t"

    # value of a C type as a field, parameter or return, without pointers
    def value_type(self, ctype, line, where):
        base = ctype.base
        if base in PRIMITIVES:
            return PRIMITIVES[base]
        if base in self.enum_names:
            return self.enum_names[base]
        if base in self.struct_names:
            return self.struct_names[base]
        if base == "bool":
            if where == "field":
                fail(line, "a bool field (the header's structs carry uint8_t flags, 0 or 1)")
            return "byte"  # C99 _Bool: one byte, 0 or 1
        if base == "void" and where == "return":
            return "void"
        fail(line, "type %r in a %s" % (ctype, where))

    def field_type(self, decl):
        ct = decl.ctype
        if ct.pointers:
            if decl.array:
                fail(decl.line, "an array of pointers")
            return ("IntPtr", None)
        if ct.base in self.callback_names:
            fail(decl.line, "a function type field that is not a pointer")
        if ct.base == "char":
            fail(decl.line, "a char field")
        cs = self.value_type(ct, decl.line, "field")
        if decl.array is None:
            return (cs, None)
        count = self.array_count(decl)
        if ct.base == "float" and count in (3, 4):
            return ("Float%d" % count, None)
        if ct.base not in PRIMITIVES or ct.base == "size_t":
            fail(decl.line, "an array of %s (C# fixed buffers hold primitive types only)" % ct.base)
        return (cs, decl.array if decl.array in self.constants else str(count))

    def array_count(self, decl):
        if re.fullmatch(r"[0-9]+", decl.array):
            return int(decl.array)
        c = self.constants.get(decl.array)
        if not c or c[1] not in ("int", "uint"):
            fail(decl.line, "array size %s is not an integer constant of the header" % decl.array)
        return int(c[2].rstrip("u"))

    # a parameter: (raw C# type, byref C# type or None, modifier for the call)
    def param_types(self, decl, func_line):
        ct = decl.ctype
        if ct.base in self.callback_names:
            if ct.pointers != 1 or decl.array:
                fail(decl.line, "callback parameter %s is not a plain function pointer" % decl.name)
            return ("IntPtr", None)
        if ct.pointers == 0 and decl.array is None:
            if ct.base == "char" or ct.base == "void":
                fail(decl.line, "parameter %s of type %r" % (decl.name, ct))
            return (self.value_type(ct, decl.line, "parameter"), None)
        # pointers, and arrays (which C passes as pointers)
        if ct.pointers and decl.array:
            fail(decl.line, "an array of pointers")
        if ct.base == "void":
            return ("IntPtr", None)
        if ct.base == "char":
            return ("byte*", ("[In] ref byte" if ct.const else "ref byte"))
        if decl.array is not None:
            count = self.array_count(decl)
            if ct.base == "float" and count in (3, 4):
                elem = "Float%d" % count
            else:
                elem = self.value_type(ct, decl.line, "parameter")
        else:
            elem = self.value_type(ct, decl.line, "parameter")
        if ct.const:
            return (elem + "*", "[In] ref " + elem)
        struct = ct.base if ct.base in self.struct_names else None
        if decl.name.startswith("out_") and not (struct and self.versioned(struct)):
            return (elem + "*", "out " + elem)
        return (elem + "*", "ref " + elem)

    def emit(self, header_path):
        h = self.h
        w = self.w
        w("// <auto-generated>")
        w("// The C# binding of include/cloth/cloth.h, written by bindings/csharp/generate.py.")
        w("// Do not edit: change the header, then run the generator (the test command does).")
        w("// </auto-generated>")
        w("using System;")
        w("using System.Runtime.InteropServices;")
        w("")
        w("namespace ClothSharp")
        w("{")
        self.emit_vectors()
        for e in h.enums:
            self.emit_enum(e)
        for c in h.callbacks:
            self.emit_callback(c)
        for s in h.structs:
            self.emit_struct(s)
        self.emit_native()
        self.emit_utf8()
        w("}")
        return "\n".join(self.out) + "\n"

    def emit_vectors(self):
        w = self.w
        for n, fields in ((3, "XYZ"), (4, "XYZW")):
            w("    /// <summary>")
            w("    /// float[%d] of the header (a vector x, y, z%s), blittable." % (n, "" if n == 3 else "; or a quaternion x, y, z, w"))
            w("    /// </summary>")
            w("    [StructLayout(LayoutKind.Sequential)]")
            w("    public struct Float%d" % n)
            w("    {")
            for f in fields:
                w("        public float %s;" % f)
            args = ", ".join("float " + f.lower() for f in fields)
            w("        public Float%d(%s)" % (n, args))
            w("        {")
            for f in fields:
                w("            %s = %s;" % (f, f.lower()))
            w("        }")
            w('        public override string ToString() { return "(" + %s + ")"; }' % ' + ", " + '.join(fields))
            # The same layout as System.Numerics' and Unity's vector and quaternion: conversions both ways,
            # so every Float3/Float4 parameter also takes them.
            for ns, vec in (("System.Numerics", "Vector3" if n == 3 else "Quaternion"),
                            ("UnityEngine", "Vector3" if n == 3 else "Quaternion")):
                full = ns + "." + vec
                lower = ns == "UnityEngine"
                if lower:
                    w("#if UNITY_5_3_OR_NEWER")
                members = [f.lower() if lower else f for f in fields]
                w("        public static implicit operator Float%d(%s v) { return new Float%d(%s); }"
                  % (n, full, n, ", ".join("v." + m for m in members)))
                w("        public static implicit operator %s(Float%d v) { return new %s(%s); }"
                  % (full, n, full, ", ".join("v." + f for f in fields)))
                if lower:
                    w("#endif")
            w("    }")
            w("")

    def emit_enum(self, e):
        name, members, docs, line = e
        w = self.w
        words = [m[0].split("_") for m in members]
        prefix = 0
        while all(len(ws) > prefix + 1 for ws in words) and len({ws[prefix] for ws in words}) == 1:
            prefix += 1
        cs = self.enum_names[name]
        self.out += doc_lines(docs, "    ")
        w("    public enum %s : int" % cs)
        w("    {")
        seen = set()
        for member, value, mdocs, mline in members:
            short = pascal_upper("_".join(member.split("_")[prefix:]))
            if not short or not re.match(r"[A-Za-z_]", short) or short in seen:
                fail(mline, "enumerator %s has no usable C# name (%r)" % (member, short))
            seen.add(short)
            self.out += doc_lines(["%s = %d%s" % (member, value, (": " + " ".join(mdocs)) if mdocs else "")], "        ")
            w("        %s = %s," % (short, value))
        w("    }")
        w("")

    def emit_callback(self, c):
        name, ret, params, docs, line = c
        cs = self.callback_names[name]
        rtype = "IntPtr" if ret.pointers else self.value_type(ret, line, "return")
        args = []
        for p in params:
            if p.array:
                fail(p.line, "an array parameter in a callback")
            if p.ctype.pointers or p.ctype.base in self.callback_names:
                t = "IntPtr"  # const char* (static or call-scoped string), void* user, callback
            else:
                t = self.value_type(p.ctype, p.line, "parameter")
            args.append("%s %s" % (t, param_name(p.name)))
        self.out += doc_lines(docs + ["C: %s. Pointers arrive as IntPtr." % name], "    ")
        self.w("    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]")
        self.w("    public delegate %s %s(%s);" % (rtype, cs, ", ".join(args)))
        self.w("")

    def default_function(self, name):
        defaults = [f for f in self.h.functions if f[1].base == name and not f[1].pointers and not f[2]
                    and f[0].startswith("cloth_default_")]
        if len(defaults) > 1:
            fail(defaults[1][4], "two cloth_default_*() functions return %s" % name)
        return defaults[0][0] if defaults else None

    def struct_rows(self, name):
        """(decl, C# type, fixed size or None, C# member name, C# field name, is_flag) per field.

        A struct with a cloth_default_*() function keeps its fields private behind properties
        that fill every default first (so `new ClothGridDesc { Columns = 8 }` is a valid
        description); a uint8_t field (a flag, 0 or 1) is a private byte behind a bool property.
        Every other field is public, as the header has it."""
        cs = self.struct_names[name]
        lazy = self.default_function(name) is not None
        rows = []
        for f in self.struct_fields[name]:
            t, fixed = self.field_type(f)
            fname = pascal(f.name)
            if fname == cs:
                fail(f.line, "field %s would share its struct's C# name" % f.name)
            flag = f.ctype.base == "uint8_t" and not f.ctype.pointers and f.array is None
            private = (lazy or flag) and fixed is None
            field = param_name(fname[:1].lower() + fname[1:]) if private else fname
            rows.append((f, t, fixed, fname, field, flag))
        return rows

    def emit_struct(self, s):
        name, fields, docs, line = s
        w = self.w
        cs = self.struct_names[name]
        rows = self.struct_rows(name)
        unsafe = any(r[2] is not None for r in rows)
        lazy = self.default_function(name) is not None
        self.out += doc_lines(docs + ["C: %s." % name], "    ")
        w("    [StructLayout(LayoutKind.Sequential)]")
        w("    public %sstruct %s%s" % ("unsafe " if unsafe else "", cs, self.equatable(name)))
        w("    {")
        for f, t, fixed, fname, field, flag in rows:
            fdocs = f.docs + ["C: %s%s." % (f.name, "[%s]" % f.array if f.array else "")]
            if fixed is not None:
                self.out += doc_lines(fdocs, "        ")
                size = ("Native." + fixed) if fixed in self.constants else fixed
                w("        public fixed %s %s[%s];" % (t, fname, size))
            elif field != fname:
                w("        %s %s;" % (t, field))
                self.out += doc_lines(fdocs, "        ")
                ptype = "bool" if flag else t
                stored = ("(structSize != 0 ? %s : Default().%s)" % (field, field)) if lazy else field
                get = ("%s != 0" % stored) if flag else stored
                value = "value ? (byte)1 : (byte)0" if flag else "value"
                fill = "EnsureDefaults(); " if lazy else ""
                w("        public %s %s { get { return %s; } set { %s%s = %s; } }" % (ptype, fname, get, fill, field, value))
            else:
                self.out += doc_lines(fdocs, "        ")
                w("        public %s %s;" % (t, fname))
        if lazy:
            w("")
            w("        /// <summary>Whether the struct holds a description (from Default(), or a property set on it);")
            w("        /// false for an all-zero struct, which the library refuses (ErrorInvalidDesc).</summary>")
            w("        public bool IsInitialized { get { return structSize != 0; } }")
            w("        /// <summary>Fills every default (and the cookie) into an all-zero struct; does nothing otherwise.")
            w("        /// Setting a property calls it first; the ClothSharp owners call it on what they are given.</summary>")
            w("        public void EnsureDefaults() { if (structSize == 0) this = Default(); }")
        for f, t, fixed, fname, field, flag in rows:
            if fixed is None:
                continue
            size = ("Native." + fixed) if fixed in self.constants else fixed
            w("")
            w("        /// <summary>Element i of %s (bounds-checked).</summary>" % fname)
            w("        public %s Get%s(int i)" % (t, fname))
            w("        {")
            w("            if ((uint)i >= (uint)%s) throw new IndexOutOfRangeException();" % size)
            w("            fixed (%s* p = %s) { return p[i]; }" % (t, fname))
            w("        }")
            w("        /// <summary>Set element i of %s (bounds-checked).</summary>" % fname)
            w("        public void Set%s(int i, %s value)" % (fname, t))
            w("        {")
            w("            if ((uint)i >= (uint)%s) throw new IndexOutOfRangeException();" % size)
            w("            fixed (%s* p = %s) { p[i] = value; }" % (t, fname))
            w("        }")
        self.emit_defaults(name, cs)
        self.emit_id_members(name, cs)
        w("    }")
        w("")

    def emit_defaults(self, name, cs):
        w = self.w
        default = self.default_function(name)
        if default:
            w("")
            w("        /// <summary>Every default set, from %s() (with the cookie; `new %s { ... }`" % (default, cs))
            w("        /// gets the same defaults for the properties it does not set).</summary>")
            w("        public static %s Default()" % cs)
            w("        {")
            w("            try { return Native.%s(); }" % default)
            w("            catch (DllNotFoundException e) { throw Native.LibraryNotFound(e); }")
            w("        }")
        elif self.versioned(name):
            w("")
            w("        /// <summary>A zero-filled struct with StructSize set, as the library expects before it fills one.</summary>")
            w("        public static %s Default()" % cs)
            w("        {")
            w("            var value = default(%s);" % cs)
            w("            value.StructSize = (uint)Marshal.SizeOf(typeof(%s));" % cs)
            w("            return value;")
            w("        }")

    def equatable(self, name):
        return " : IEquatable<%s>" % self.struct_names[name] if any(e[1] == name for e in self.h.equalities) else ""

    def emit_id_members(self, name, cs):
        w = self.w
        nulls = [n for n in self.h.null_ids if n[1] == name]
        eqs = [e for e in self.h.equalities if e[1] == name]
        fields = self.struct_fields[name]
        for n in nulls:
            if n[2] != len(fields):
                fail(n[3], "%s initialises %d of %d fields" % (n[0], n[2], len(fields)))
            w("")
            w("        /// <summary>%s: the all-zero id, which names nothing.</summary>" % n[0])
            w("        public static readonly %s Null = default(%s);" % (cs, cs))
            w("        /// <summary>Whether every field is zero (the null id).</summary>")
            w("        public bool IsNull { get { return %s; } }" % " && ".join("%s == 0" % pascal(f.name) for f in fields))
        for e in eqs:
            fname, type_name, a, b, body, line = e
            # The body must compare every field, a.f == b.f, joined by &&.
            expected = []
            for f in fields:
                expected += [a, ".", f.name, "==", b, ".", f.name, "&&"]
            expected = ["return"] + expected[:-1] + [";"]
            if body != expected:
                fail(line, "%s does not compare exactly every field of %s with ==" % (fname, type_name))
            cmp = " && ".join("a.%s == b.%s" % (pascal(f.name), pascal(f.name)) for f in fields)
            w("")
            w("        /// <summary>%s(): every field equal.</summary>" % fname)
            w("        public static bool operator ==(%s a, %s b) { return %s; }" % (cs, cs, cmp))
            w("        public static bool operator !=(%s a, %s b) { return !(a == b); }" % (cs, cs))
            w("        public bool Equals(%s other) { return this == other; }" % cs)
            w("        public override bool Equals(object obj) { return obj is %s && this == (%s)obj; }" % (cs, cs))
            hash_expr = "(int)" + pascal(fields[0].name)
            for f in fields[1:]:
                hash_expr = "(%s * 31) ^ (int)%s" % (hash_expr, pascal(f.name))
            w("        public override int GetHashCode() { unchecked { return %s; } }" % hash_expr)
            w("        public override string ToString()")
            w("        {")
            w('            return "%s(" + %s + ")";' % (cs, ' + ", " + '.join(pascal(f.name) for f in fields)))
            w("        }")

    def emit_native(self):
        h = self.h
        w = self.w
        w("    /// <summary>")
        w("    /// Every function and constant of cloth.h, as the header names them. Functions return")
        w("    /// ClothResult codes (the ClothSharp wrappers turn them into exceptions).")
        w("    /// </summary>")
        w("    public static unsafe partial class Native")
        w("    {")
        w("        /// <summary>The native library: cloth.dll, libcloth.so, libcloth.dylib; linked in on iOS.</summary>")
        w("#if (UNITY_IOS || UNITY_WEBGL) && !UNITY_EDITOR")
        w('        public const string Library = "__Internal";')
        w("#else")
        w('        public const string Library = "cloth";')
        w("#endif")
        w("")
        w("        /// <summary>")
        w("        /// A DllNotFoundException that says which file is needed and where it was looked for, in")
        w("        /// place of the runtime's bare one (thrown by Default() and the ClothSharp owners).")
        w("        /// </summary>")
        w("        public static DllNotFoundException LibraryNotFound(DllNotFoundException inner)")
        w("        {")
        w("            string file;")
        w("            string path = null;")
        w("            switch (Environment.OSVersion.Platform)")
        w("            {")
        w('                case PlatformID.Win32NT: file = "cloth.dll"; path = "PATH"; break;')
        w('                case PlatformID.MacOSX: file = "libcloth.dylib"; path = "DYLD_LIBRARY_PATH"; break;')
        w("                default:")
        w('                    file = System.IO.Directory.Exists("/System/Library") ? "libcloth.dylib" : "libcloth.so";')
        w('                    path = file == "libcloth.so" ? "LD_LIBRARY_PATH" : "DYLD_LIBRARY_PATH";')
        w("                    break;")
        w("            }")
        w("            string variable = Environment.GetEnvironmentVariable(path);")
        w('            string message = "The cloth native library (" + file + ", the C API of cloth.h " +')
        w('                             CLOTH_VERSION_MAJOR + "." + CLOTH_VERSION_MINOR + " or newer) could not be loaded. " +')
        w('                             "DllImport(\\"" + Library + "\\") looks for " + file + " next to the program (" +')
        w("                             AppDomain.CurrentDomain.BaseDirectory + \"), in \" + path + \" (\" +")
        w('                             (string.IsNullOrEmpty(variable) ? "not set" : variable) + ") and in the system\'s library " +')
        w('                             "directories; under Unity, in the package\'s Runtime/Plugins/<platform>/ with that " +')
        w('                             "platform enabled in the plugin\'s import settings. The runtime said: " + inner.Message;')
        w("            return new DllNotFoundException(message, inner);")
        w("        }")
        w("")
        for name, ctype, literal, docs, line in h.constants:
            self.out += doc_lines(docs, "        ")
            w("        public const %s %s = %s;" % (ctype, name, literal))
        w("")
        for n in h.null_ids:
            w("        /// <summary>%s (header-only in C): all-zero.</summary>" % n[0])
            w("        public static readonly %s %s = default(%s);" % (self.struct_names[n[1]], n[0], self.struct_names[n[1]]))
        for e in h.equalities:
            cs = self.struct_names[e[1]]
            w("        /// <summary>%s (header-only in C): every field equal.</summary>" % e[0])
            w("        public static bool %s(%s a, %s b) { return a == b; }" % (e[0], cs, cs))
        w("")
        for f in h.functions:
            self.emit_function(f)
        self.emit_layout_check()
        w("    }")

    def dllimport(self, name):
        return (
            "        [DllImport(Library, EntryPoint = \"%s\", CallingConvention = CallingConvention.Cdecl, "
            "ExactSpelling = true)]" % name
        )

    def emit_function(self, f):
        name, ret, params, docs, line = f
        w = self.w
        if ret.pointers:
            if ret.base != "char" or not ret.const:
                fail(line, "%s returns %r (only const char* strings are returned by pointer)" % (name, ret))
            rtype = "IntPtr"
        else:
            if ret.base in self.callback_names:
                fail(line, "%s returns a function type" % name)
            rtype = self.value_type(ret, line, "return")
        raw, byref = [], []
        has_byref = False
        string_params = []
        for p in params:
            r, b = self.param_types(p, line)
            pn = param_name(p.name)
            raw.append("%s %s" % (r, pn))
            byref.append("%s %s" % (b if b else r, pn))
            has_byref = has_byref or b is not None
            if p.ctype.base == "char" and p.ctype.const:
                string_params.append(p.name)
        extra = []
        if ret.base == "bool" or any(p.ctype.base == "bool" for p in params):
            extra.append("bool is C99 _Bool: one byte, 0 or 1 (byte here).")
        if rtype == "IntPtr" and ret.base == "char":
            extra.append("Returns a library-owned NUL-terminated string: never freed; %s_str() copies it." % name)
        self.out += doc_lines(docs + extra, "        ")
        w(self.dllimport(name))
        w("        public static extern %s %s(%s);" % (rtype, name, ", ".join(raw)))
        if has_byref:
            w("        /// <summary>%s with ref/out parameters: no unsafe code at the call site (pass ref array[0]" % name)
            w("        /// for an array). Use the pointer overload to pass null.</summary>")
            w(self.dllimport(name))
            w("        public static extern %s %s(%s);" % (rtype, name, ", ".join(byref)))
        if string_params:
            sig, call, pre = [], [], []
            for p, b in zip(params, byref):
                pn = param_name(p.name)
                if p.name in string_params:
                    sig.append("string %s" % pn)
                    pre.append("            byte[] %s_utf8 = Utf8.ToNulTerminated(%s);" % (p.name, pn))
                    call.append("ref %s_utf8[0]" % p.name)
                else:
                    sig.append(b)
                    mod = "out" if b.startswith("out ") else "ref" if b.startswith(("ref ", "[In] ref ")) else ""
                    call.append(("%s %s" % (mod, pn)) if mod else pn)
            w("        /// <summary>%s with %s as a C# string (passed as NUL-terminated UTF-8).</summary>"
              % (name, ", ".join(string_params)))
            w("        public static %s %s(%s)" % (rtype, name, ", ".join(sig)))
            w("        {")
            self.out += pre
            w("            %s%s(%s);" % ("return " if rtype != "void" else "", name, ", ".join(call)))
            w("        }")
        if rtype == "IntPtr" and ret.base == "char":
            args = ", ".join(param_name(p.name) for p in params)
            sig = ", ".join(raw)
            w("        /// <summary>%s, copied into a C# string (the library's string is not freed).</summary>" % name)
            w("        public static string %s_str(%s) { return Utf8.ToString(%s(%s)); }" % (name, sig, name, args))
        w("")

    def emit_utf8(self):
        self.out += """
    /// <summary>The strings of the C API: NUL-terminated UTF-8 (cloth.h, "Other languages").</summary>
    public static unsafe class Utf8
    {
        /// <summary>Copy a library-owned NUL-terminated UTF-8 string; null for IntPtr.Zero. Never frees it.</summary>
        public static string ToString(IntPtr text)
        {
            if (text == IntPtr.Zero) return null;
            byte* p = (byte*)text;
            int length = 0;
            while (p[length] != 0) ++length;
            return System.Text.Encoding.UTF8.GetString(p, length);
        }

        /// <summary>s as NUL-terminated UTF-8 bytes, for a const char* parameter.</summary>
        public static byte[] ToNulTerminated(string s)
        {
            if (s == null) throw new ArgumentNullException("s");
            int length = System.Text.Encoding.UTF8.GetByteCount(s);
            var bytes = new byte[length + 1];
            System.Text.Encoding.UTF8.GetBytes(s, 0, s.Length, bytes, 0);
            return bytes;
        }
    }""".split("\n")

    def emit_layout_check(self):
        w = self.w
        kinds = [e for e in self.h.enums if e[0] == "cloth_struct_kind"]
        if not kinds:
            fail(1, "no cloth_struct_kind: struct layouts could not be checked")
        mapped = {}
        for member, value, docs, mline in kinds[0][1]:
            target = " ".join(docs).strip()
            if target in self.struct_names:
                if target in mapped:
                    fail(mline, "two struct kinds name %s" % target)
                mapped[target] = (member, value)
        missing = [s for s in self.struct_names if s not in mapped]
        if missing:
            fail(kinds[0][3], "no cloth_struct_kind names %s (its layout could not be checked)" % ", ".join(missing))
        kind_cs = self.enum_names["cloth_struct_kind"]
        w("        /// <summary>Each struct of the header with its cloth_struct_kind.</summary>")
        w("        public static readonly Type[] StructTypes = new Type[]")
        w("        {")
        for s in self.struct_names:
            w("            typeof(%s)," % self.struct_names[s])
        w("        };")
        w("        /// <summary>The cloth_struct_kind of each entry of StructTypes.</summary>")
        w("        public static readonly %s[] StructKinds = new %s[]" % (kind_cs, kind_cs))
        w("        {")
        for s in self.struct_names:
            w("            (%s)%d, // %s" % (kind_cs, mapped[s][1], mapped[s][0]))
        w("        };")
        w("")
        w("        /// <summary>")
        w("        /// Compares the size of every struct of this binding with the loaded library's")
        w("        /// (cloth_struct_size) and returns one line per mismatch; empty when all agree.")
        w("        /// </summary>")
        w("        public static string[] CheckStructLayouts()")
        w("        {")
        w("            var mismatches = new System.Collections.Generic.List<string>();")
        w("            for (int i = 0; i < StructTypes.Length; ++i)")
        w("            {")
        w("                ulong native = (ulong)cloth_struct_size(StructKinds[i]);")
        w("                ulong managed = (ulong)Marshal.SizeOf(StructTypes[i]);")
        w("                if (native != managed)")
        w("                {")
        w('                    mismatches.Add(StructTypes[i].Name + ": C# " + managed + " bytes, library " + native);')
        w("                }")
        w("            }")
        w("            return mismatches.ToArray();")
        w("        }")
        w("")
        w("        /// <summary>")
        w("        /// One line per struct (\"cloth_x size N\") and per field (\"cloth_x.field offset N\"), with the")
        w("        /// C names, as C# lays them out: the test command compares them with the same lines")
        w("        /// printed by a C program compiled against cloth.h (generate.py --c-layouts).")
        w("        /// </summary>")
        w("        public static string[] FieldLayouts()")
        w("        {")
        w("            return new string[]")
        w("            {")
        for s in self.struct_names:
            cs = self.struct_names[s]
            w('                "%s size " + Marshal.SizeOf(typeof(%s)),' % (s, cs))
            for f, t, fixed, fname, field, flag in self.struct_rows(s):
                w('                "%s.%s offset " + (long)Marshal.OffsetOf(typeof(%s), "%s"),' % (s, f.name, cs, field.lstrip("@")))
        w("            };")
        w("        }")


# The ClothSharp owners (ClothSharp.cs) by the handle type of their functions' first parameter,
# with the prefix their functions' names take after it.
OWNERS = {
    "cloth_world_id": ("World", "cloth_world_"),
    "cloth_fabric_id": ("Fabric", "cloth_fabric_"),
    "cloth_id": ("Cloth", "cloth_"),
    "cloth_body_id": ("Body", "cloth_body_"),
    "cloth_collider_id": ("Collider", "cloth_collider_"),
}
# Scalars a property passes as they are (integers keep the hand-written layer's int and its
# range checks: ClothSharp.cs).
PROPERTY_SCALARS = ("float", "double")


def property_pairs(header, emitter):
    """The get/set pairs of one shape, as owner properties: (owner, property, C# type, get, set, docs).

    A pair is PREFIX get_X and PREFIX set_X of one owner, both returning cloth_result, whose set takes
    (owner id, const T* value) and whose get takes (owner id, T* out_value), T a struct; or whose set
    takes (owner id, T value) and whose get (owner id, T* out_value), T a float, double or enum. Other
    pairs (two outputs, a second id, an integer) stay hand-written in ClothSharp.cs."""
    functions = {f[0]: f for f in header.functions}
    pairs = []
    for name, ret, params, docs, line in header.functions:
        if not params or params[0].ctype.pointers or params[0].ctype.base not in OWNERS:
            continue
        owner, prefix = OWNERS[params[0].ctype.base]
        if not name.startswith(prefix + "get_"):
            continue
        x = name[len(prefix) + len("get_"):]
        setter = functions.get(prefix + "set_" + x)
        if setter is None:
            continue
        get_params, set_params = params, setter[2]
        if ret.base != "cloth_result" or setter[1].base != "cloth_result":
            continue
        if len(get_params) != 2 or len(set_params) != 2 or set_params[0].ctype.base != get_params[0].ctype.base:
            continue
        out, value = get_params[1], set_params[1]
        if out.ctype.pointers != 1 or out.ctype.const or out.array or value.array:
            continue
        t = out.ctype.base
        if value.ctype.base != t:
            continue
        if t in emitter.struct_names:
            if value.ctype.pointers != 1 or not value.ctype.const:
                continue
            cs = emitter.struct_names[t]
            set_ = ["value.EnsureDefaults();"] if emitter.default_function(t) else []
            set_.append("ClothException.Check(Native.%s(Id, ref value));" % setter[0])
        elif t in PROPERTY_SCALARS or t in emitter.enum_names:
            if value.ctype.pointers:
                continue
            cs = emitter.enum_names.get(t, PRIMITIVES.get(t))
            set_ = ["ClothException.Check(Native.%s(Id, value));" % setter[0]]
        else:
            continue
        # The getter's output as the generated Native signature passes it: `out`, or `ref` from a
        # struct whose struct_size the library reads first (Default() sets it).
        if emitter.param_types(out, line)[1].startswith("out "):
            get = ["%s value;" % cs, "ClothException.Check(Native.%s(Id, out value));" % name]
        else:
            start = "%s.Default()" % cs if emitter.versioned(t) else "default(%s)" % cs
            get = ["%s value = %s;" % (cs, start), "ClothException.Check(Native.%s(Id, ref value));" % name]
        get.append("return value;")
        pairs.append((owner, pascal(x), cs, get, set_, setter[3] + ["C: %s, %s." % (name, setter[0])]))
    return pairs


def owner_properties(header, emitter):
    """ClothSharp.g.cs: the owners' get/set properties, one partial class per owner that has any."""
    out = [
        "// <auto-generated>",
        "// The ClothSharp owners' get/set properties, written by bindings/csharp/generate.py from",
        "// each cloth_get_X / cloth_set_X pair of include/cloth/cloth.h that has one shape (a struct, or",
        "// a float, double or enum). The rest of each owner is hand-written in ClothSharp.cs.",
        "// Do not edit: change the header, then run the generator (the test command does).",
        "// </auto-generated>",
        "namespace ClothSharp",
        "{",
    ]
    pairs = property_pairs(header, emitter)
    owners = list(dict.fromkeys(p[0] for p in pairs))
    for i, owner in enumerate(owners):
        if i:
            out.append("")
        out.append("    public sealed partial class %s" % owner)
        out.append("    {")
        first = True
        for o, prop, cs, get, set_, docs in pairs:
            if o != owner:
                continue
            if not first:
                out.append("")
            first = False
            out += doc_lines(docs, "        ")
            out.append("        public %s %s" % (cs, prop))
            out.append("        {")
            for accessor, body in (("get", get), ("set", set_)):
                out.append("            %s" % accessor)
                out.append("            {")
                out += ["                " + statement for statement in body]
                out.append("            }")
            out.append("        }")
        out.append("    }")
    out.append("}")
    return "\n".join(out) + "\n", len(pairs)


def c_layouts(header):
    """A C program printing the lines of Native.FieldLayouts() from the C compiler's layout."""
    lines = ["/* Written by bindings/csharp/generate.py --c-layouts: the C side of the layout check. */",
             "#include <stddef.h>", "#include <stdio.h>", "#include <cloth/cloth.h>", "", "int main(void) {"]
    for name, fields, docs, line in header.structs:
        lines.append('    printf("%s size %%lu\\n", (unsigned long)sizeof(%s));' % (name, name))
        for f in fields:
            lines.append('    printf("%s.%s offset %%lu\\n", (unsigned long)offsetof(%s, %s));'
                         % (name, f.name, name, f.name))
    lines += ["    return 0;", "}", ""]
    return "\n".join(lines)


def generate(header_path):
    with open(header_path, encoding="utf-8") as f:
        text = f.read()
    header = Parser(tokenize(text)).parse()
    if not header.functions:
        raise BindError("%s: no CLOTH_API functions found" % header_path)
    emitter = Emitter(header)
    code = emitter.emit(header_path)
    return header, code, owner_properties(header, emitter)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--header", default=DEFAULT_HEADER, help="cloth.h to bind (default: the repository's)")
    ap.add_argument("--out", required=True, help="the C# file to write")
    ap.add_argument("--c-layouts", help="also write a C program printing every struct's size and field offsets")
    ap.add_argument("--properties", help="also write the owners' get/set properties (ClothSharp.g.cs), which "
                    "ClothSharp.cs needs")
    args = ap.parse_args()
    try:
        header, code, (properties, property_count) = generate(args.header)
    except BindError as e:
        print("generate.py: %s" % e, file=sys.stderr)
        return 1
    if args.c_layouts:
        with open(args.c_layouts, "w", encoding="utf-8", newline="\n") as f:
            f.write(c_layouts(header))
    for path, text in ((args.out, code), (args.properties, properties)):
        if path:
            os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
            with open(path, "w", encoding="utf-8", newline="\n") as f:
                f.write(text)
    print(
        "generate.py: %d functions, %d structs, %d enums, %d callbacks, %d constants -> %s"
        % (len(header.functions), len(header.structs), len(header.enums), len(header.callbacks),
           len(header.constants), args.out)
    )
    if args.properties:
        print("generate.py: %d get/set properties -> %s" % (property_count, args.properties))
    return 0


if __name__ == "__main__":
    sys.exit(main())
