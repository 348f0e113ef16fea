// A user program built against the installed package: the patent's tetrahedron of faces.
#include <Soup_topology/Adjacency_tables.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <vector>

int main()
{
  const std::vector<std::array<std::size_t, 3>> triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  const Soup_topology::Adjacency_tables adj(triangles, 4);
  std::cout << "installed package: " << adj.number_of_triangles() << " triangles, closed = " << adj.is_closed() << "\n";
  return adj.is_closed() ? EXIT_SUCCESS : EXIT_FAILURE;
}
