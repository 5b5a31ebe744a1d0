//===- SemaTest.cpp - Semantic analysis unit tests ------------------------===//

#include "FrontendTestUtil.h"

#include <gtest/gtest.h>

using namespace simit::frontend;
using simit::frontend::test::Compilation;

namespace {

// Declarations most tests build on (6 lines; snippets start on line 7).
const std::string kDecls = "element V\n  x : vector[3](float);\n  m : float;\n"
                           "end\nelement E\n  k : float;\n";
const std::string kSets = "end\nextern verts : set{V}; extern edges : "
                          "set{E}(verts, verts);\nextern other : set{V};\n";
// Snippet bodies start on line 11 inside `func t(...)` on line 10.
std::string inFunc(const std::string &params, const std::string &body) {
  return kDecls + kSets + "func t(" + params + ")\n" + body + "end\n";
}

/// The type sema gave the value of the first assignment in `body`.
std::string typeOfValue(const std::string &params, const std::string &body) {
  Compilation c(inFunc(params, body));
  if (!c.ok)
    return "error: " + c.allErrors();
  for (auto &s : c.program->funcs.back()->body->stmts)
    if (auto *a = llvm::dyn_cast<AssignStmt>(s.get()))
      return a->value->type->str();
  return "none";
}

// --- Types of expressions -------------------------------------------------

TEST(SemaTypes, Literals) {
  EXPECT_EQ(typeOfValue("", "x = 1;\n"), "int");
  EXPECT_EQ(typeOfValue("", "x = 1.5;\n"), "float");
  EXPECT_EQ(typeOfValue("", "x = true;\n"), "bool");
  EXPECT_EQ(typeOfValue("", "x = \"s\";\n"), "string");
  EXPECT_EQ(typeOfValue("", "x = <1.0, 2.0>;\n"), "complex");
}

TEST(SemaTypes, DenseLiteralOrientation) {
  EXPECT_EQ(typeOfValue("", "x = [1.0, 2.0];\n"), "tensor[2](float)'");
  EXPECT_EQ(typeOfValue("", "x = [1.0, 2.0]';\n"), "tensor[2](float)");
  EXPECT_EQ(typeOfValue("", "x = [1, 2; 3, 4];\n"), "tensor[2,2](int)");
  EXPECT_EQ(typeOfValue("", "x = [2.0; 3.0];\n"), "tensor[2,1](float)");
  EXPECT_EQ(typeOfValue("", "x = [[1, 2], [3, 4]];\n"), "tensor[2,2](int)");
}

TEST(SemaTypes, TransposedLiteralFoldsRowMajor) {
  Compilation c(inFunc("", "x = [1, 2, 3; 4, 5, 6]';\n"));
  ASSERT_TRUE(c.ok) << c.allErrors();
  auto &a = llvm::cast<AssignStmt>(*c.program->funcs[0]->body->stmts[0]);
  auto *d = llvm::cast<DenseLiteral>(a.value.get());
  EXPECT_EQ(d->shape, (std::vector<int64_t>{3, 2}));
  EXPECT_EQ(d->intValues, (std::vector<int64_t>{1, 4, 2, 5, 3, 6}));
}

TEST(SemaTypes, NegatedLiteralFolds) {
  Compilation c(inFunc("", "x = -[0.5, 1.0];\n y = -2147483648;\n"));
  ASSERT_TRUE(c.ok) << c.allErrors();
  auto &a = llvm::cast<AssignStmt>(*c.program->funcs[0]->body->stmts[0]);
  auto *d = llvm::cast<DenseLiteral>(a.value.get());
  EXPECT_EQ(d->floatValues, (std::vector<double>{-0.5, -1.0}));
}

TEST(SemaTypes, IntLiteralOutOfRange) {
  EXPECT_ERROR(inFunc("", "x = 2147483648;\n"), "11:5", "32 bits");
}

TEST(SemaTypes, ScalarBroadcast) {
  EXPECT_EQ(typeOfValue("v : vector[3](float)", "x = 1.0 - v;\n"),
            "tensor[3](float)");
  EXPECT_EQ(typeOfValue("v : vector[3](float)", "x = v / 2.0;\n"),
            "tensor[3](float)");
  EXPECT_EQ(typeOfValue("v : vector[3](float)", "x = 2.0 / v;\n"),
            "tensor[3](float)");
}

TEST(SemaTypes, ProductTable) {
  const std::string p = "r : vector[3](float)', c : vector[3](float), M : "
                        "matrix[3,3](float), N : matrix[3,2](float)";
  EXPECT_EQ(typeOfValue(p, "x = r * c;\n"), "float");
  EXPECT_EQ(typeOfValue(p, "x = c * r;\n"), "tensor[3,3](float)");
  EXPECT_EQ(typeOfValue(p, "x = M * c;\n"), "tensor[3](float)");
  EXPECT_EQ(typeOfValue(p, "x = r * M;\n"), "tensor[3](float)'");
  EXPECT_EQ(typeOfValue(p, "x = M * N;\n"), "tensor[3,2](float)");
  EXPECT_EQ(typeOfValue(p, "x = N' * M;\n"), "tensor[2,3](float)");
}

TEST(SemaTypes, ProductErrors) {
  const std::string p = "r : vector[3](float)', c : vector[3](float), M : "
                        "matrix[3,3](float), T : tensor[2,2,2](float)";
  EXPECT_ERROR(inFunc(p, "x = r * r;\n"), "11:7", "two row vectors");
  EXPECT_ERROR(inFunc(p, "x = c * c;\n"), "11:7", "two column vectors");
  EXPECT_ERROR(inFunc(p, "x = M * r;\n"), "11:7", "matrix by a row vector");
  EXPECT_ERROR(inFunc(p, "x = c * M;\n"), "11:7", "column vector by a matrix");
  EXPECT_ERROR(inFunc(p, "x = T * T;\n"), "11:7", "order 3");
  EXPECT_ERROR(inFunc(p, "x = M * [1.0, 2.0]';\n"), "11:7",
               "dimension mismatch");
  EXPECT_ERROR(inFunc(p, "x = 1.5 * 2;\n"), "11:9", "incompatible");
}

TEST(SemaTypes, BlockedSystemProducts) {
  const std::string p = "K : matrix[verts,verts](matrix[3,3](float)), x : "
                        "vector[verts](vector[3](float))";
  EXPECT_EQ(typeOfValue(p, "y = K * x;\n"),
            "tensor[verts](tensor[3](float))");
  EXPECT_EQ(typeOfValue(p, "y = x' * x;\n"), "float");
  EXPECT_EQ(typeOfValue(p, "y = K';\n"),
            "tensor[verts,verts](tensor[3,3](float))");
}

TEST(SemaTypes, TransposeSwapsBlocks) {
  EXPECT_EQ(typeOfValue("A : matrix[verts,other](matrix[2,3](int))",
                        "y = A';\n"),
            "tensor[other,verts](tensor[3,2](int))");
}

TEST(SemaTypes, SetFieldIsGlobalVector) {
  EXPECT_EQ(typeOfValue("", "y = verts.x;\n"),
            "tensor[verts](tensor[3](float))");
  EXPECT_EQ(typeOfValue("", "y = verts.m;\n"), "tensor[verts](float)");
}

TEST(SemaTypes, Solve) {
  EXPECT_EQ(typeOfValue("A : matrix[verts,other](float), b : "
                        "vector[verts](float)",
                        "y = A \\ b;\n"),
            "tensor[other](float)");
  EXPECT_ERROR(inFunc("A : matrix[2,2](float)", "y = A \\ [1.0, 2.0];\n"),
               "11:7", "column vector");
}

TEST(SemaTypes, SlicesAndOrientation) {
  const std::string p = "M : matrix[3,4](float), T : tensor[2,3,4](float)";
  EXPECT_EQ(typeOfValue(p, "y = M(1,:);\n"), "tensor[4](float)'");
  EXPECT_EQ(typeOfValue(p, "y = M(:,1);\n"), "tensor[3](float)");
  EXPECT_EQ(typeOfValue(p, "y = T(0,:,:);\n"), "tensor[3,4](float)");
}

TEST(SemaTypes, BlockReads) {
  const std::string p = "K : matrix[verts,verts](matrix[3,3](float))";
  EXPECT_EQ(typeOfValue(p, "for q in verts\n y = K(q,q);\n end\n"), "none");
  EXPECT_ACCEPTS(inFunc(p, "for q in verts\n y = K(q,q)(0,1) + 1.0;\n end\n"));
}

TEST(SemaTypes, StringConcatenation) {
  EXPECT_EQ(typeOfValue("", "y = \"a\" + \"b\";\n"), "string");
  EXPECT_ERROR(inFunc("", "y = \"a\" - \"b\";\n"), "11:9", "numeric");
}

TEST(SemaTypes, ElementWiseErrors) {
  EXPECT_ERROR(inFunc("", "y = true + false;\n"), "11:10", "numeric");
  EXPECT_ERROR(inFunc("", "y = [1 2] + [1.0 2.0];\n"), "11:11",
               "incompatible");
  EXPECT_ERROR(inFunc("", "y = [1.0 2.0] + [1.0 2.0]';\n"), "11:15",
               "incompatible");
  EXPECT_ERROR(inFunc("a : vector[verts](float), b : vector[other](float)",
                      "y = a + b;\n"),
               "11:7", "incompatible");
}

TEST(SemaTypes, LogicAndComparison) {
  EXPECT_EQ(typeOfValue("a : int", "y = 0 < a <= 5;\n"), "bool");
  EXPECT_ERROR(inFunc("", "y = 1 or 0;\n"), "11:7", "boolean");
  EXPECT_ERROR(inFunc("", "y = not 4;\n"), "11:5", "boolean");
  EXPECT_ERROR(inFunc("", "y = 2 < 2.5;\n"), "11:7", "cannot compare");
  EXPECT_ERROR(inFunc("v : vector[2](float)", "y = v == v;\n"), "11:7",
               "scalars");
  EXPECT_ERROR(inFunc("", "y = -true;\n"), "11:5", "numeric negation");
  EXPECT_ERROR(inFunc("x : float", "y = x ^ 2.0;\n"), "11:7", "not supported");
}

TEST(SemaTypes, NoImplicitConversion) {
  EXPECT_ERROR(inFunc("", "var n : int = 2.5;\n"), "11:15",
               "cannot initialize");
}

// --- Declarations, scopes --------------------------------------------------

TEST(SemaDecls, Redefinitions) {
  EXPECT_ERROR("element G\nend\nelement G\nend\n", "3:9", "redefinition");
  EXPECT_ERROR("extern w : int;\nextern w : int;\n", "2:8", "redefinition");
  EXPECT_ERROR("func r()\nend\nfunc r()\nend\n", "3:6", "redefinition");
  EXPECT_ERROR("func det()\nend\n", "1:6", "intrinsic");
  EXPECT_ERROR("func g<N>(N : int)\nend\n", "1:11", "redefinition");
  EXPECT_ERROR("element G\n a : int;\n a : int;\nend\n", "3:2",
               "redefinition of field");
  EXPECT_ERROR(inFunc("", "var k = 1;\nvar k = 2;\n"), "12:5", "redefinition");
}

TEST(SemaDecls, ShadowingInInnerBlocks) {
  EXPECT_ACCEPTS(inFunc("a : int", "var a = 1.0;\nif true\n var a = 2;\nend\n"));
}

TEST(SemaDecls, NamesInvisibleAfterBlock) {
  EXPECT_ERROR(inFunc("", "if true\n b = 1;\nend\nc = b;\n"), "14:5",
               "undeclared variable 'b'");
}

TEST(SemaDecls, DoWhileConditionCannotSeeBody) {
  EXPECT_ERROR(inFunc("", "do\n d = true;\nend while d\n"), "13:11",
               "undeclared variable 'd'");
}

TEST(SemaDecls, Undeclared) {
  EXPECT_ERROR(inFunc("", "r = q + 1;\n"), "11:5", "undeclared variable 'q'");
  EXPECT_ERROR(kDecls + kSets + "func f(t : tensor[V](int))\nend\n", "10:19",
               "element type");
  EXPECT_ERROR("func f(c : (Cog*2))\nend\n", "1:13", "undeclared element");
}

TEST(SemaDecls, NoRecursionOrForwardCalls) {
  EXPECT_ERROR("func a()\n b();\nend\nfunc b()\nend\n", "2:2",
               "undeclared function 'b'");
  EXPECT_ERROR("func a()\n a();\nend\n", "2:2", "undeclared function 'a'");
}

TEST(SemaDecls, VariableShadowsFunction) {
  EXPECT_ACCEPTS("func sq(x : float) -> (r : float)\n r = x * x;\nend\n"
                 "func t(sq : vector[2](float)) -> (r : float)\n r = sq(1);\n"
                 "end\n");
}

TEST(SemaDecls, GlobalConstants) {
  EXPECT_ACCEPTS("const a = 3;\nconst b : vector[3](float) = [1.0, 2.0, "
                 "3.0];\nconst c : tensor[1,2,1](int) = [4; 5];\nconst d = "
                 "-[0.5, 1.0]';\n");
  EXPECT_ERROR("const k : int = 2 * 3;\n", "1:19", "must be a literal");
  EXPECT_ERROR("const v : vector[3](float) = 0.0;\n", "1:30",
               "from a scalar");
}

TEST(SemaDecls, ExternKinds) {
  EXPECT_ACCEPTS(kDecls + kSets + "extern dt : vector[2](float);\n");
  EXPECT_ERROR(kDecls + kSets + "extern e : E;\n", "10:12",
               "set, grid or tensor");
}

TEST(SemaDecls, ExportedGeneric) {
  EXPECT_ERROR("export func f<N>()\nend\n", "1:13", "cannot be generic");
}

TEST(SemaDecls, SetTypes) {
  EXPECT_ERROR(kDecls + kSets + "extern w : int;\nextern s : set{E}(w);\n",
               "11:19", "expected a set");
  EXPECT_ERROR(kDecls + kSets + "extern s : set{E}(verts*0);\n", "10:25",
               "positive arity");
  EXPECT_ERROR(kDecls + kSets + "extern g : grid[1]{E}(edges);\n", "10:23",
               "zero-cardinality");
  EXPECT_ACCEPTS(kDecls + kSets +
                 "extern faces : set{E}(edges, edges, edges);\n");
}

TEST(SemaDecls, TensorTypeRules) {
  EXPECT_ERROR("func f(x : tensor[3,3](float)')\nend\n", "1:12",
               "must be a vector");
  EXPECT_ERROR(kDecls + kSets + "func f(x : tensor[verts](tensor[2,2](float)))"
                                "\nend\n",
               "10:26", "block order mismatch");
  EXPECT_ERROR("element G\n t : (G*2);\nend\n", "2:6", "tensor type");
}

TEST(SemaDecls, TupleTypes) {
  EXPECT_ERROR(kDecls + kSets + "func f(t : (E*0))\nend\n", "10:15",
               "positive length");
  EXPECT_ERROR(kDecls + kSets + "func f(t : (a : E, a : V))\nend\n", "10:20",
               "redefinition of tuple member");
}

TEST(SemaDecls, RepeatCountsAreBounded) {
  // Each repetition is a member of the type: 2^31 - 1 would take gigabytes.
  EXPECT_ERROR(kDecls + kSets + "func f(t : (E*2147483647))\nend\n", "10:15",
               "a tuple's length can be at most 1024, found 2147483647");
  EXPECT_ERROR(kDecls + kSets + "extern s : set{E}(verts*5000);\n", "10:25",
               "an edge set's arity can be at most 1024, found 5000");
  EXPECT_ERROR(kDecls + kSets + "extern g : grid[100000]{E}(verts);\n",
               "10:17", "a grid's dimension count can be at most 1024");
  EXPECT_ACCEPTS(kDecls + kSets + "func f(t : (E*1024))\nend\n");
}

TEST(SemaDecls, VarMustBeTensor) {
  EXPECT_ERROR(inFunc("el : E", "var e2 = el;\n"), "11:10",
               "must have a tensor type");
}

TEST(SemaDecls, LocalConstBroadcastAndRelaxedShape) {
  EXPECT_ACCEPTS(inFunc("", "const z : vector[3](float) = 0.0;\nconst r : "
                            "vector[3](float) = [1.0, 2.0, 3.0];\n"));
}

// --- Assignment and writability ------------------------------------------

TEST(SemaAssign, ImplicitDeclarations) {
  Compilation c(inFunc("", "a = 1;\nb, d = two();\n"));
  EXPECT_FALSE(c.ok); // two() is undeclared here
  EXPECT_ACCEPTS("func two() -> (a : int, b : float)\n a = 1; b = 1.0;\nend\n"
                 "func f()\n x, y = two();\n z = x + 1;\n w = y * 2.0;\nend\n");
}

TEST(SemaAssign, ImplicitLocalIsImmutable) {
  EXPECT_ERROR(inFunc("", "t = 1;\nt = 2;\n"), "12:1", "not writable");
  EXPECT_ERROR(inFunc("", "t = [1, 2];\nt(0) = 5;\n"), "12:1", "not writable");
}

TEST(SemaAssign, ReadOnlyTargets) {
  EXPECT_ERROR(inFunc("p : float", "p = 1.0;\n"), "11:1", "not writable");
  EXPECT_ERROR(inFunc("", "const c = 1;\nc = 2;\n"), "12:1", "not writable");
  EXPECT_ERROR(inFunc("", "3 = 4;\n"), "11:1", "not writable");
  EXPECT_ERROR(inFunc("", "for p in verts\n p.m = 1.0;\nend\n"), "12:2",
               "not writable");
  EXPECT_ACCEPTS(inFunc("inout p : float", "p = 1.0;\n"));
  EXPECT_ACCEPTS(inFunc("", "for p in verts\n verts.m(p) = 1.0;\nend\n"));
}

TEST(SemaAssign, MultipleValues) {
  const std::string two =
      "func two() -> (a : float, b : float)\n a = 1.0; b = 2.0;\nend\n";
  EXPECT_ERROR(two + "func f()\n a = two();\nend\n", "5:6",
               "2 values to 1 target");
  EXPECT_ACCEPTS(two + "func f()\n var x = 0.0;\n var y = 0.0;\n x, y = "
                       "two();\nend\n");
}

TEST(SemaAssign, WrongTypes) {
  EXPECT_ERROR("func count() -> (c : int)\n c = 1;\nend\nfunc f()\n var x : "
               "float = 0.0;\n x = count();\nend\n",
               "6:6", "cannot assign");
  EXPECT_ERROR(inFunc("el : E", "q = el;\n"), "11:5", "non-tensor");
  EXPECT_ERROR(inFunc("", "var v : vector[2](float) = [1.0, 2.0];\n"), "11:28",
               "cannot initialize");
}

TEST(SemaAssign, BlockAndBroadcastWrites) {
  EXPECT_ACCEPTS(inFunc("", "var M : matrix[3,3](float) = 0.0;\nM(0,0) = 1.0;"
                            "\nverts.m = 0.0;\n"));
}

TEST(SemaAssign, SliceAssignmentIsRejected) {
  EXPECT_ERROR(inFunc("", "var A : matrix[2,2](float);\nA(:,0) = [1.0, "
                          "2.0]';\n"),
               "12:1", "slice");
}

TEST(SemaAssign, OpaqueValues) {
  EXPECT_ACCEPTS(inFunc("A : matrix[verts,verts](float)",
                        "h = lu<verts>(A);\nx = lusolve<verts,verts>(h, "
                        "verts.m);\nlufree(h);\n"));
}

// --- Control flow ---------------------------------------------------------

TEST(SemaControl, Conditions) {
  EXPECT_ERROR(inFunc("", "while 1\nend\n"), "11:7", "boolean");
  EXPECT_ERROR(inFunc("", "if true\nelif 0.5\nend\n"), "12:6", "boolean");
  EXPECT_ERROR(inFunc("", "do\nend while 2\n"), "12:11", "boolean");
}

TEST(SemaControl, ForLoops) {
  EXPECT_ERROR(inFunc("n : int", "for i in n\nend\n"), "11:10",
               "expected a set");
  EXPECT_ERROR(inFunc("", "for i in 0.0:1.0\nend\n"), "11:10", "integral");
  EXPECT_ERROR(inFunc("", "for i in 0:3\n i = 2;\nend\n"), "12:2",
               "not writable");
  EXPECT_ACCEPTS(inFunc("", "for i in 0:3\n x = i;\nend\n"));
}

TEST(SemaControl, Print) {
  EXPECT_ERROR(inFunc("", "print verts;\n"), "11:7", "cannot print");
  EXPECT_ACCEPTS(inFunc("", "print 1, 2.0, \"s\", [1 2], verts.m;\n"));
}

// --- Accesses --------------------------------------------------------------

TEST(SemaAccess, IndexRules) {
  EXPECT_ERROR(inFunc("t : vector[3](float)", "y = t(1.5);\n"), "11:7",
               "integral");
  EXPECT_ERROR(inFunc("t : vector[3](float)", "y = t(1, 2);\n"), "11:5",
               "expected 1 index");
  EXPECT_ERROR(inFunc("A : matrix[verts,verts](float)", "y = A(0, 0);\n"),
               "11:7", "element of set 'verts'");
  EXPECT_ERROR(inFunc("", "y = verts(1);\n"), "11:5", "not a tensor");
  EXPECT_ERROR(inFunc("n : int", "y = n.f;\n"), "11:7", "not a set or element");
  EXPECT_ERROR(inFunc("w : V", "y = w.nosuch;\n"), "11:7", "undefined field");
  EXPECT_ERROR(inFunc("n : int", "y = n[1];\n"), "11:6", "set reads");
}

TEST(SemaAccess, OriginsFromLoops) {
  EXPECT_ERROR(inFunc("X : vector[verts](float)",
                      "for e in other\n y = X(e);\nend\n"),
               "12:8", "inferred to be of set 'other'");
}

TEST(SemaAccess, OriginsInferredForParameters) {
  EXPECT_ERROR(kDecls + kSets +
                   "func f(p : V, X : vector[verts](float), Y : "
                   "vector[other](float)) -> (r : float)\n r = X(p) + Y(p);\n"
                   "end\n",
               "11:15", "inferred to be of set 'verts'");
}

TEST(SemaAccess, MatrixFieldIsNotASetField) {
  EXPECT_ERROR("element G\n M : matrix[2,2](float);\nend\nextern S : set{G};\n"
               "func f()\n y = S.M;\nend\n",
               "6:8", "scalar and vector");
}

TEST(SemaAccess, Tuples) {
  EXPECT_ERROR(inFunc("t : (V*2)", "y = t(1.0).m;\n"), "11:7", "must be an int");
  EXPECT_ERROR(inFunc("t : (V*2)", "y = t(2).m;\n"), "11:7", "out of range");
  EXPECT_ERROR(inFunc("t : (a : V, b : V)", "y = t.c.m;\n"), "11:5",
               "undefined tuple member");
  EXPECT_ACCEPTS(inFunc("t : (a : V, b : V)", "y = t.b.x(1) + t.a.m;\n"));
}

// --- Calls -----------------------------------------------------------------

TEST(SemaCalls, ArgumentRules) {
  const std::string g = "func g(x : int) -> (r : int)\n r = x;\nend\n"
                        "func h()\nend\n";
  EXPECT_ERROR(g + "func f()\n a = sqrt(1.0, 2.0);\nend\n", "7:6",
               "expects 1 argument");
  EXPECT_ERROR(g + "func f()\n a = g();\nend\n", "7:6", "expects 1 argument");
  EXPECT_ERROR(g + "func f()\n a = g(2.0);\nend\n", "7:8", "expects 'int'");
  EXPECT_ERROR(g + "func f()\n a = g(h());\nend\n", "7:8", "non-void");
}

TEST(SemaCalls, NormAndDot) {
  EXPECT_ERROR(inFunc("M : matrix[3,3](float)", "y = norm(M);\n"), "11:10",
               "numeric vector");
  EXPECT_ERROR(inFunc("a : vector[3](float), b : vector[2](float)",
                      "y = dot(a, b);\n"),
               "11:5", "same type");
  EXPECT_EQ(typeOfValue("a : vector[3](float)", "y = dot(a, a') + norm(a');\n"),
            "float");
}

TEST(SemaCalls, InoutArguments) {
  const std::string k = "func k(inout y : float)\nend\n";
  EXPECT_ERROR(k + "func f()\n const c = 1.0;\n k(c);\nend\n", "5:4",
               "must be writable");
  EXPECT_ERROR(k + "func f()\n var x = 1.0;\n k(x + 1.0);\nend\n", "5:6",
               "must be writable");
  EXPECT_ACCEPTS(k + "func f()\n var x = 1.0;\n k(x);\nend\n");
}

TEST(SemaCalls, IntrinsicSignatures) {
  EXPECT_ACCEPTS(inFunc("A : matrix[3,3](float), a : vector[3](float)",
                        "y = det(A) + atan2(1.0, 2.0);\ni = mod(3, 2);\n"
                        "z = inv(A) * cross(a, a);\n"
                        "c = complexNorm(createComplex(1.0, 2.0));\n"
                        "t = storeTime(0, clock());\n"));
  EXPECT_ERROR(inFunc("A : matrix[2,2](float)", "y = det(A);\n"), "11:9",
               "expects 'tensor[3,3](float)'");
}

// --- Generics ---------------------------------------------------------------

TEST(SemaGenerics, InferredFromArgumentsAndInstantiated) {
  Compilation c("func twice<N>(v : vector[N](float)) -> (w : vector[N](float))"
                "\n w = 2.0 * v;\nend\nfunc f()\n a = twice([1.0, 2.0]');\n b "
                "= twice<3>([1.0, 2.0, 3.0]');\n c = twice([3.0, 4.0]');\nend\n");
  ASSERT_TRUE(c.ok) << c.allErrors();
  const FuncDecl &twice = *c.program->funcs[0];
  ASSERT_EQ(twice.instances.size(), 2u);
  EXPECT_EQ(twice.instances[0]->mangledName, "twice_2");
  EXPECT_EQ(twice.instances[1]->mangledName, "twice_3");
  EXPECT_EQ(twice.instances[0]->params[0]->type->str(), "tensor[2](float)");
  auto &a = llvm::cast<AssignStmt>(*c.program->funcs[1]->body->stmts[0]);
  EXPECT_EQ(llvm::cast<CallExpr>(*a.value).func, twice.instances[0].get());
}

TEST(SemaGenerics, CheckedGenerically) {
  EXPECT_ERROR("func f<N, M>(a : vector[N](float), b : vector[M](float)) -> "
               "(c : vector[N](float))\n c = a + b;\nend\n",
               "2:8", "incompatible");
}

TEST(SemaGenerics, InstanceErrorsAreReported) {
  EXPECT_ERROR("func f<0:N>(a : vector[N](float)) -> (r : float)\n r = a(2);"
               "\nend\nfunc g()\n x = f([1.0, 2.0]');\nend\n",
               "2:8", "index 2 is out of range");
}

TEST(SemaGenerics, ExplicitAndUnresolved) {
  const std::string gv = "func gv<N>(v : vector[N](float)) -> (r : float)\n r "
                         "= 0.0;\nend\n";
  EXPECT_ERROR(gv + "func f(u : vector[3](float))\n x = gv<1,2>(u);\nend\n",
               "5:6", "too many generic arguments");
  EXPECT_ERROR(gv + "func f()\n x = gv(3);\nend\n", "5:6",
               "unable to resolve");
  EXPECT_ERROR("func gm<N>(m : matrix[N,N](float)) -> (r : float)\n r = 0.0;\n"
               "end\nfunc f(m : matrix[2,1](float))\n x = gm(m);\nend\n",
               "5:9", "expects 'tensor[2,2](float)'");
}

TEST(SemaGenerics, RangeParameterAsIntAndLoop) {
  EXPECT_ACCEPTS("func s<0:K>(v : vector[K](float)) -> (r : float)\n r = 0.0;"
                 "\n for i in 0:K\n  r = r + v(i);\n end\nend\n"
                 "func f()\n x = s([1.0, 2.0]');\nend\n");
  EXPECT_ERROR("func s<0:K>()\n for i in K\n end\nend\n", "2:11",
               "iterated as '0:K'");
}

TEST(SemaGenerics, BindingFromEndpointOrigins) {
  Compilation c(kDecls + kSets +
                "func asm<T>(e : E, b : (V*2)) -> (A : matrix[T,T](float))\n"
                " A(b(0), b(1)) = e.k;\nend\nexport func main()\n K = map asm "
                "to edges reduce +;\nend\n");
  ASSERT_TRUE(c.ok) << c.allErrors();
  ASSERT_EQ(c.program->funcs[0]->instances.size(), 1u);
  EXPECT_EQ(c.program->funcs[0]->instances[0]->mangledName, "asm_verts");
}

// --- Maps and apply ---------------------------------------------------------

TEST(SemaMaps, ResolvedMap) {
  Compilation c(kDecls + kSets +
                "func s(e : E, p : (V*2)) -> (K : matrix[verts,verts](float))"
                "\n K(p(0), p(1)) = e.k;\nend\nexport func main()\n K = map s "
                "to edges reduce +;\nend\n");
  ASSERT_TRUE(c.ok) << c.allErrors();
  auto &a = llvm::cast<AssignStmt>(*c.program->funcs[1]->body->stmts[0]);
  auto &map = llvm::cast<MapExpr>(*a.value);
  EXPECT_EQ(map.targetSet->name, "edges");
  EXPECT_EQ(map.endpointForm, MapExpr::EndpointForm::Unnamed);
  EXPECT_TRUE(map.reduce);
  EXPECT_EQ(map.type->str(), "tensor[verts,verts](float)");
}

TEST(SemaMaps, Errors) {
  const std::string d = kDecls + kSets + "extern w : float;\n";
  EXPECT_ERROR(d + "func h(e : V)\nend\nfunc f()\n map h to w;\nend\n", "14:11",
               "expected a set");
  EXPECT_ERROR(d + "func h(e : E, p : (V*1))\nend\nfunc f()\n map h to "
                   "edges;\nend\n",
               "14:11", "2 endpoints");
  EXPECT_ERROR(d + "func h(e : V) -> (r : vector[verts](float))\n r(e) = 1.0;"
                   "\nend\nfunc f()\n apply h to verts;\nend\n",
               "15:8", "non-void");
  EXPECT_ERROR(d + "func h(x : int, e : V)\nend\nfunc f()\n map h(1.0) to "
                   "verts;\nend\n",
               "14:8", "expects 'int'");
  EXPECT_ERROR(d + "func h(e : V) -> (r : vector[verts](float))\n r(e) = 1.0;"
                   "\nend\nfunc f()\n r = map h to other reduce +;\nend\n",
               "15:15", "expects elements of set 'verts'");
  EXPECT_ERROR(d + "func f()\n map nosuch to verts;\nend\n", "12:6",
               "undeclared function");
}

TEST(SemaMaps, HeterogeneousNeedsNamedTuple) {
  const std::string d = kDecls + kSets +
                        "extern links : set{E}(verts, other);\n";
  EXPECT_ERROR(d + "func h(e : E, p : (V*2))\nend\nfunc f()\n map h to links;"
                   "\nend\n",
               "14:11", "named endpoint tuple");
  EXPECT_ACCEPTS(d + "func h(e : E, p : (a : V, b : V))\nend\nfunc f()\n map h "
                     "to links;\nend\n");
}

TEST(SemaMaps, ApplyWithInoutWrites) {
  EXPECT_ACCEPTS(kDecls + kSets +
                 "func h(inout e : E, inout p : (V*2))\n e.k = 1.0;\n p(0).m = "
                 "2.0;\nend\nfunc f()\n apply h to edges;\nend\n");
  EXPECT_ERROR(kDecls + kSets +
                   "func h(e : E)\n e.k = 1.0;\nend\n",
               "11:2", "not writable");
}

TEST(SemaMaps, GridStencil) {
  EXPECT_ACCEPTS("element P\n v : float;\nend\nelement L\n w : float;\nend\n"
                 "extern pts : set{P};\nextern gr : grid[2]{L}(pts);\n"
                 "func st(p : P, g : grid[2]{L}(pts)) -> (A : "
                 "matrix[pts,pts](float))\n A(p, p) = g[0,0;0,1].w;\n A(p, "
                 "pts[1,0]) = -1.0;\nend\nfunc f()\n A = map st to pts through "
                 "gr;\nend\n");
}

// --- Index variables -------------------------------------------------------

TEST(SemaIndexVars, FreeAndReductionVariables) {
  Compilation c(inFunc("A : matrix[3,3](float), B : matrix[3,3](float)",
                       "ivar i; ivar j; ivar k;\nvar C : matrix[3,3](float);\n"
                       "C(i,j) = A(i,k) * B(k,j);\n"));
  ASSERT_TRUE(c.ok) << c.allErrors();
  auto &a = llvm::cast<AssignStmt>(*c.program->funcs[0]->body->stmts[4]);
  EXPECT_TRUE(a.isIndexExpr);
  EXPECT_EQ(a.freeIndexVars.size(), 2u);
  ASSERT_EQ(a.reductionIndexVars.size(), 1u);
  EXPECT_EQ(a.reductionIndexVars[0]->name, "k");
}

TEST(SemaIndexVars, Errors) {
  const std::string p = "v : vector[3](float), A : matrix[3,3](float)";
  EXPECT_ERROR(inFunc(p, "ivar i;\ni = 0;\n"), "12:1", "not writable");
  EXPECT_ERROR(inFunc(p, "ivar i;\nx = i;\n"), "12:5", "not a value");
  EXPECT_ERROR(inFunc(p, "ivar i;\nif v(i) == 0.0\nend\n"), "12:6",
               "outside an assignment");
  EXPECT_ERROR(inFunc(p, "ivar i; ivar j;\nvar C : matrix[3,3](float);\n"
                         "C(A(i,j), 0) = 1.0;\n"),
               "13:5", "nested read");
  EXPECT_ERROR(inFunc(p, "ivar i;\nvar C : matrix[3,3](float);\nC(:,i) = v;\n"),
               "13:5", "mixed with slices");
  EXPECT_ERROR(inFunc(p, "ivar i; ivar j;\nvar C : matrix[3,3](float);\n"
                         "C(i,j) = A(i,j) / A(j,i);\n"),
               "13:17", "not allowed in an index expression");
  EXPECT_ERROR(inFunc(p, "var i : int;\nivar i;\n"), "12:6", "redefinition");
  EXPECT_ERROR(inFunc(p, "ivar i;\nx = sin(i);\n"), "12:9", "not a value");
}

// --- Test lines --------------------------------------------------------------

TEST(SemaTestLines, MustBeLiterals) {
  EXPECT_ERROR("const c = 1.0;\n%! f(c) == 1.0;\nfunc f(x : float) -> (r : "
               "float)\n r = x;\nend\n",
               "2:6", "must be a literal");
  Compilation ok("%! f(-[1.0, 2.0]', <1.0, -1.0>) == -3;\nfunc f(v : "
                 "vector[2](float), c : complex) -> (r : int)\n r = 0;\nend\n");
  ASSERT_TRUE(ok.ok) << ok.allErrors();
  EXPECT_EQ(ok.program->tests[0].func, ok.program->funcs[0].get());
}

TEST(SemaTestLines, UnknownFunctionIsLeftToTheRunner) {
  Compilation c("%! nosuch(1) == 1;\n");
  EXPECT_TRUE(c.ok) << c.allErrors();
  EXPECT_EQ(c.program->tests[0].func, nullptr);
}

TEST(SemaDiagnostics, SeveralErrorsSortedByPosition) {
  Compilation c(inFunc("", "b = zz;\na = yy;\n"));
  ASSERT_EQ(c.errors.size(), 2u);
  EXPECT_EQ(c.errors[0].substr(0, 5), "11:5:");
  EXPECT_EQ(c.errors[1].substr(0, 5), "12:5:");
}

} // namespace
