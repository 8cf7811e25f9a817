// Placeholder translation unit so the library target exists before its sources land.
namespace attenuvis { namespace visgraph_placeholder { int unused = 0; } }
