!> This rank's part of the mesh: owned zones plus one layer of ghost zones
!> (every zone sharing a node with an owned zone), their nodes, the node ->
!> corner lists that make the force gather independent of the rank count, and
!> the halo and I/O plans. Built by mesh_distribute.
module mesh_local
  use core_kinds, only: i8
  use mesh_global, only: NAME_LEN
  use parallel_halo, only: halo_t
  use parallel_redistribute, only: redistribute_t
  implicit none
  private

  !> Local mesh. Owned items come first, each group sorted by global id.
  type, public :: mesh_t
    integer :: nnode = 0 !< local nodes (owned + ghost)
    integer :: nnode_owned = 0 !< nodes 1..nnode_owned are owned
    integer :: nzone = 0 !< local zones (owned + ghost)
    integer :: nzone_owned = 0 !< zones 1..nzone_owned are owned
    integer(i8) :: nnode_global = 0 !< nodes of the whole mesh
    integer(i8) :: nzone_global = 0 !< zones of the whole mesh
    integer(i8), allocatable :: node_gid(:) !< 1-based global node ids
    integer(i8), allocatable :: zone_gid(:) !< 1-based global zone ids
    integer, allocatable :: node_owner(:) !< owner rank of each local node
    integer, allocatable :: zone_node(:, :) !< (8, nzone) local node indices
    integer, allocatable :: zone_block(:) !< block index of each zone
    integer, allocatable :: corner_start(:) !< CSR over owned nodes, size nnode_owned+1
    integer, allocatable :: corner_list(:) !< corner 8 (z-1) + c, sorted by zone global id
    integer, allocatable :: face_neighbour(:, :) !< (6, nzone) zone across each face:
        !< local index, 0 on the mesh boundary, -1 when the neighbour is not local
    integer, allocatable :: face_neighbour_face(:, :) !< (6, nzone) the neighbour's face
    integer :: nset = 0 !< face sets
    character(len=NAME_LEN), allocatable :: set_name(:)
    integer, allocatable :: set_start(:) !< CSR over local faces of each set
    integer, allocatable :: set_zone(:) !< local zone of each face
    integer, allocatable :: set_face(:) !< face 1..6 of that zone
    integer(i8), allocatable :: set_ord(:) !< position of that face in its set's global list
    type(halo_t) :: node_halo !< refresh of ghost node data
    type(halo_t) :: zone_halo !< refresh of ghost zone data (restart, limiter)
    type(redistribute_t) :: node_io !< owned nodes <-> dump blocks
    type(redistribute_t) :: zone_io !< owned zones <-> dump blocks
  end type mesh_t

end module mesh_local
