// A user program built against the installed package: the patent's tetrahedron of faces, and the
// version of the headers against the version CMake found.
#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/version.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

int consumer_all_headers_compiled();

static_assert(SOUP_TOPOLOGY_VERSION_MAJOR == CONSUMER_EXPECTED_VERSION_MAJOR &&
                SOUP_TOPOLOGY_VERSION_MINOR == CONSUMER_EXPECTED_VERSION_MINOR &&
                SOUP_TOPOLOGY_VERSION_PATCH == CONSUMER_EXPECTED_VERSION_PATCH,
              "version.h disagrees with the version of the installed CMake package");

int main()
{
  if(std::strcmp(SOUP_TOPOLOGY_VERSION, CONSUMER_EXPECTED_VERSION) != 0) {
    std::cerr << "version.h says " << SOUP_TOPOLOGY_VERSION << ", the CMake package " << CONSUMER_EXPECTED_VERSION << "\n";
    return EXIT_FAILURE;
  }
  const std::vector<std::array<std::size_t, 3>> triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  const Soup_topology::Adjacency_tables adj(triangles, 4);
  std::cout << "installed package " << SOUP_TOPOLOGY_VERSION << ": " << adj.number_of_triangles()
            << " triangles, closed = " << adj.is_closed() << ", all headers = " << consumer_all_headers_compiled() << "\n";
  return adj.is_closed() ? EXIT_SUCCESS : EXIT_FAILURE;
}
