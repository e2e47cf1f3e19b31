// Run with no libcloth.so on the library path (ctest cloth_csharp.MissingLibrary):
// the first call into the library throws a DllNotFoundException whose
// message names the file that is needed and where it was looked for, from
// the World constructor and from a description's Default() alike.
using System;
using ClothSharp;

static class MissingLibrary
{
    static int Main()
    {
        int failures = 0;
        Action[] firstCalls = { () => new World().Dispose(), () => ClothGridDesc.Default(), () => ClothLibrary.Verify() };
        string[] names = { "new World()", "ClothGridDesc.Default()", "ClothLibrary.Verify()" };
        for (int i = 0; i < firstCalls.Length; ++i)
        {
            try
            {
                firstCalls[i]();
                Console.WriteLine("FAILED: " + names[i] + " found a cloth library; run this with none on the path");
                ++failures;
            }
            catch (DllNotFoundException e)
            {
                string m = e.Message;
                bool ok = m.Contains("libcloth.so") && m.Contains("LD_LIBRARY_PATH") &&
                          m.Contains(AppDomain.CurrentDomain.BaseDirectory) && m.Contains("Runtime/Plugins") &&
                          e.InnerException is DllNotFoundException;
                Console.WriteLine((ok ? "ok - " : "FAILED: ") + names[i] + " says which file and where: " + m);
                if (!ok) ++failures;
            }
        }
        return failures == 0 ? 0 : 1;
    }
}
