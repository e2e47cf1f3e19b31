// Prints every struct's size and every field's offset as the C# binding
// lays them out (Native.FieldLayouts); check.sh layouts compares the lines
// with those of a C program compiled against cloth.h.
using System;
using ClothSharp;

static class Layouts
{
    static void Main()
    {
        foreach (string line in Native.FieldLayouts()) Console.WriteLine(line);
    }
}
