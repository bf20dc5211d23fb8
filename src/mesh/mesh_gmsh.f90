!> Reader of a whole Gmsh ASCII mesh, format 2.2 and 4.1, into a
!> global_mesh_t on the calling rank: for tests that compare with the whole
!> mesh (setup_mesh with whole, tests/unit/test_mesh_gmsh). Runs read a
!> Gmsh file in chunks (mesh_gmsh_stream), with the same parser
!> (mesh_gmsh_parse) and the same checks, distributed.
!>
!> Zones are the 8-node hexahedra (Gmsh element type 5); each must lie in one
!> 3D physical group, and the 3D groups, in order of their physical tags, are
!> the blocks. Quadrilaterals (type 3) in 2D physical groups become face sets
!> named after their groups, each quad matched to the hexahedron face with the
!> same four nodes. Nodes used by the hexahedra are renumbered 1..nnode in
!> increasing order of their Gmsh tags; zones keep the order of the file.
!> Gmsh's hexahedron node order is the VTK order used by mesh_geometry.
!> Points, lines, triangles, other volume elements and second-order elements
!> are ignored when they are in no physical group or in a 0D/1D group.
!> Names of physical groups are required in 4.1 files; in 2.2 files an
!> unnamed group N is called 'physical_N'.
module mesh_gmsh
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_sort, only: sort_order
  use core_text, only: itoa => to_text, i8toa => to_text
  use mesh_geometry, only: hex_volume, HEX_FACE_NODES
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_gmsh_parse, only: gmsh_header_t, gmsh_sink_t, gmsh_parse, gmsh_groups, &
      sorted_key, same_cycle, lower_bound, find_sorted, MAX_REPORT
  implicit none
  private
  public :: mesh_read_gmsh

  !> The whole file's nodes and elements, before checking and renumbering.
  type, extends(gmsh_sink_t) :: whole_sink_t
    integer :: nnode = 0 !< nodes in the file
    integer(i8), allocatable :: node_tag(:)
    real(rk), allocatable :: node_xyz(:, :) !< (3, nnode)
    integer :: nhex = 0
    integer(i8), allocatable :: hex_tag(:), hex_node(:, :) !< node tags (8, nhex)
    integer, allocatable :: hex_group(:) !< 3D physical tag, 0 = none
    integer :: nquad = 0 !< quads in 2D physical groups (one entry per group)
    integer(i8), allocatable :: quad_tag(:), quad_node(:, :) !< node tags (4, nquad)
    integer, allocatable :: quad_group(:) !< 2D physical tag
  contains
    procedure :: nodes_begin => whole_nodes_begin
    procedure :: node => whole_node
    procedure :: nodes_done => whole_nodes_done
    procedure :: hex => whole_hex
    procedure :: quad => whole_quad
    procedure :: reserve => whole_reserve
  end type whole_sink_t

contains

  !> Read an ASCII Gmsh mesh (.msh 2.2 or 4.1). Every problem goes to status with a
  !> message starting "mesh file '<path>': "; on any problem the mesh is left empty.
  subroutine mesh_read_gmsh(path, mesh, block_names, status)
    character(len=*), intent(in) :: path !< the .msh file
    type(global_mesh_t), intent(inout) :: mesh !< the mesh read; zone_block indexes block_names
    !> Names of the 3D physical groups in order of their physical tags.
    character(len=NAME_LEN), allocatable, intent(out) :: block_names(:)
    type(status_t), intent(inout) :: status !< problems are added here
    type(gmsh_header_t) :: head
    type(whole_sink_t) :: data
    character(len=:), allocatable :: prefix
    logical :: parsed
    integer :: count0

    prefix = "mesh file '"//trim(path)//"': "
    count0 = status%count
    call mesh%free()
    allocate(block_names(0))
    call gmsh_parse(path, prefix, head, data, status, parsed)
    if (parsed) call build_mesh(head, data, prefix, mesh, block_names, status)
    if (status%count > count0) then
      call mesh%free()
      if (allocated(block_names)) deallocate(block_names)
      allocate(block_names(0))
    end if
  end subroutine mesh_read_gmsh

  ! ---------------------------------------------------------------------------
  ! The sink: every node and element kept
  ! ---------------------------------------------------------------------------

  !> Room for n nodes.
  subroutine whole_nodes_begin(data, lo, n, ok)
    class(whole_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: lo
    integer, intent(in) :: n
    logical, intent(out) :: ok
    integer :: stat
    allocate(data%node_tag(n), data%node_xyz(3, n), stat=stat)
    ok = stat == 0
    data%nnode = 0
  end subroutine whole_nodes_begin

  !> Append one node.
  subroutine whole_node(data, tag, xyz)
    class(whole_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: tag
    real(rk), intent(in) :: xyz(3)
    data%nnode = data%nnode + 1
    data%node_tag(data%nnode) = tag
    data%node_xyz(:, data%nnode) = xyz
  end subroutine whole_node

  !> Nothing to do at the end of $Nodes.
  subroutine whole_nodes_done(data)
    class(whole_sink_t), intent(inout) :: data
  end subroutine whole_nodes_done

  !> Room for more elements.
  subroutine whole_reserve(data, nhex, nquad)
    class(whole_sink_t), intent(inout) :: data
    integer, intent(in) :: nhex, nquad
    if (nhex > 0) call reserve_hex(data, data%nhex + nhex)
    if (nquad > 0) call reserve_quad(data, data%nquad + nquad)
  end subroutine whole_reserve

  !> Room for at least n hexahedra.
  subroutine reserve_hex(data, n)
    type(whole_sink_t), intent(inout) :: data
    integer, intent(in) :: n
    integer(i8), allocatable :: tag(:), node(:, :)
    integer, allocatable :: group(:)
    integer :: capacity
    if (allocated(data%hex_tag)) then
      if (size(data%hex_tag) >= n) return
    end if
    capacity = max(n, 2 * data%nhex, 64)
    allocate(tag(capacity), node(8, capacity), group(capacity))
    if (data%nhex > 0) then
      tag(1:data%nhex) = data%hex_tag(1:data%nhex)
      node(:, 1:data%nhex) = data%hex_node(:, 1:data%nhex)
      group(1:data%nhex) = data%hex_group(1:data%nhex)
    end if
    call move_alloc(tag, data%hex_tag)
    call move_alloc(node, data%hex_node)
    call move_alloc(group, data%hex_group)
  end subroutine reserve_hex

  !> Room for at least n quadrilaterals.
  subroutine reserve_quad(data, n)
    type(whole_sink_t), intent(inout) :: data
    integer, intent(in) :: n
    integer(i8), allocatable :: tag(:), node(:, :)
    integer, allocatable :: group(:)
    integer :: capacity
    if (allocated(data%quad_tag)) then
      if (size(data%quad_tag) >= n) return
    end if
    capacity = max(n, 2 * data%nquad, 64)
    allocate(tag(capacity), node(4, capacity), group(capacity))
    if (data%nquad > 0) then
      tag(1:data%nquad) = data%quad_tag(1:data%nquad)
      node(:, 1:data%nquad) = data%quad_node(:, 1:data%nquad)
      group(1:data%nquad) = data%quad_group(1:data%nquad)
    end if
    call move_alloc(tag, data%quad_tag)
    call move_alloc(node, data%quad_node)
    call move_alloc(group, data%quad_group)
  end subroutine reserve_quad

  !> Append one hexahedron.
  subroutine whole_hex(data, tag, nodes, phys)
    class(whole_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(8)
    integer, intent(in) :: phys
    call reserve_hex(data, data%nhex + 1)
    data%nhex = data%nhex + 1
    data%hex_tag(data%nhex) = tag
    data%hex_node(:, data%nhex) = nodes
    data%hex_group(data%nhex) = phys
  end subroutine whole_hex

  !> Append one quadrilateral of the 2D group phys.
  subroutine whole_quad(data, tag, nodes, phys)
    class(whole_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(4)
    integer, intent(in) :: phys
    call reserve_quad(data, data%nquad + 1)
    data%nquad = data%nquad + 1
    data%quad_tag(data%nquad) = tag
    data%quad_node(:, data%nquad) = nodes
    data%quad_group(data%nquad) = phys
  end subroutine whole_quad

  ! ---------------------------------------------------------------------------
  ! Building the mesh
  ! ---------------------------------------------------------------------------

  !> Check what was read, renumber the nodes, match quads to hex faces, fill mesh.
  subroutine build_mesh(head, data, prefix, mesh, block_names, status)
    type(gmsh_header_t), intent(in) :: head
    type(whole_sink_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(inout) :: block_names(:)
    type(status_t), intent(inout) :: status
    integer, allocatable :: block_tags(:), set_tags(:), node_order(:), new_id(:)
    character(len=NAME_LEN), allocatable :: set_names(:)
    integer(i8), allocatable :: keys(:, :), node_keys(:, :)
    integer, allocatable :: order(:)
    integer :: z, k, i, nbad, nused, p
    logical, allocatable :: used(:)
    real(rk) :: volume
    character(len=24) :: text

    call reserve_hex(data, 1)
    call reserve_quad(data, 1)
    ! Blocks and face sets.
    call gmsh_groups(head, prefix, int(data%nhex, i8), data%hex_group(1:data%nhex), &
        data%quad_group(1:data%nquad), block_tags, set_tags, block_names, set_names, status)
    if (data%nhex == 0) return

    nbad = 0
    do z = 1, data%nhex
      if (data%hex_group(z) == 0) then
        call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedron '//i8toa(data%hex_tag(z))// &
            ' is in no 3D physical group (every zone needs a block: define Physical Volumes)')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'hexahedra in no 3D physical group')

    ! Nodes: file index of every tag, then compact ids of those used by hexahedra.
    allocate(node_keys(1, data%nnode))
    node_keys(1, :) = data%node_tag(1:data%nnode)
    call sort_order(node_keys, node_order)
    nbad = 0
    do i = 2, data%nnode
      if (node_keys(1, node_order(i)) == node_keys(1, node_order(i - 1))) then
        call status%add_capped(nbad, MAX_REPORT, prefix//'node tag '//i8toa(node_keys(1, node_order(i)))// &
            ' appears more than once in $Nodes')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'repeated node tags')
    allocate(used(data%nnode), new_id(data%nnode))
    used = .false.
    nbad = 0
    do z = 1, data%nhex
      do k = 1, 8
        p = find_tag(node_keys, node_order, data%hex_node(k, z))
        if (p == 0) then
          call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedron '//i8toa(data%hex_tag(z))// &
              ' refers to node '//i8toa(data%hex_node(k, z))//', which is not in $Nodes')
        else
          used(p) = .true.
        end if
      end do
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'unknown node tags in hexahedra')
    if (nbad > 0) return

    new_id = 0
    nused = 0
    do i = 1, data%nnode
      if (used(node_order(i))) then
        nused = nused + 1
        new_id(node_order(i)) = nused
      end if
    end do
    mesh%nnode = nused
    mesh%nzone = data%nhex
    allocate(mesh%coordinates(3, nused), mesh%connectivity(8, data%nhex))
    allocate(mesh%zone_block(data%nhex))
    do i = 1, data%nnode
      if (new_id(i) > 0) mesh%coordinates(:, new_id(i)) = data%node_xyz(:, i)
    end do
    nbad = 0
    do i = 1, data%nnode
      if (new_id(i) > 0) then
        if (.not. all(ieee_is_finite(data%node_xyz(:, i)))) then
          call status%add_capped(nbad, MAX_REPORT, prefix//'node '//i8toa(data%node_tag(i))// &
              ' has a coordinate that is not a finite number')
        end if
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'nodes with non-finite coordinates')
    if (nbad > 0) return
    do z = 1, data%nhex
      do k = 1, 8
        p = find_tag(node_keys, node_order, data%hex_node(k, z))
        mesh%connectivity(k, z) = int(new_id(p), ik)
      end do
      mesh%zone_block(z) = int(find_sorted(block_tags, data%hex_group(z)), ik)
    end do

    ! The same hexahedron twice: 2.2 files repeat the elements of a volume that is in
    ! several physical groups.
    allocate(keys(4, mesh%nzone))
    do z = 1, mesh%nzone
      keys(:, z) = sorted_key(int(mesh%connectivity(:, z)))
    end do
    call sort_order(keys, order)
    nbad = 0
    do i = 2, mesh%nzone
      if (all(keys(:, order(i)) == keys(:, order(i - 1)))) then
        call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedra '//i8toa(data%hex_tag(order(i - 1)))// &
            ' and '//i8toa(data%hex_tag(order(i)))//' have the same nodes (is a volume in '// &
            'several 3D physical groups?)')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'repeated hexahedra')
    deallocate(keys, order)

    ! Orientation: Gmsh and impact3d share the node order, so a volume <= 0 is an error.
    nbad = 0
    do z = 1, mesh%nzone
      volume = hex_volume(mesh%coordinates(:, mesh%connectivity(:, z)))
      if (volume <= 0.0_rk) then
        write(text, '(es12.4)') volume
        call status%add_capped(nbad, MAX_REPORT, prefix//'hexahedron '//i8toa(data%hex_tag(z))// &
            ' has volume '//trim(adjustl(text))//' <= 0: its nodes are inverted or '// &
            'degenerate (impact3d does not reorder them)')
      end if
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'hexahedra with volume <= 0')

    call build_sets(data, prefix, node_keys, node_order, new_id, set_tags, set_names, mesh, &
        status)
  end subroutine build_mesh

  !> Match every quadrilateral to a hexahedron face and fill the face sets of mesh.
  subroutine build_sets(data, prefix, node_keys, node_order, new_id, set_tags, set_names, &
      mesh, status)
    type(whole_sink_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    integer(i8), intent(in) :: node_keys(:, :) !< (1, nnode in file): the node tags
    integer, intent(in) :: node_order(:) !< sorting permutation of node_keys
    integer, intent(in) :: new_id(:) !< compact id of each file node, 0 if unused
    integer, intent(in) :: set_tags(:) !< 2D physical tags of the sets, sorted
    character(len=NAME_LEN), intent(in) :: set_names(:)
    type(global_mesh_t), intent(inout) :: mesh
    type(status_t), intent(inout) :: status
    integer(i8), allocatable :: face_keys(:, :), entry_keys(:, :)
    integer, allocatable :: face_order(:), quad_set(:), quad_face(:), entry_order(:)
    integer :: z, f, q, k, p, nbad_node, nbad_face, nset, s, n, best, candidate, m, last
    integer :: nodes(4), file_index
    logical :: unknown

    nset = size(set_tags)
    ! Every hexahedron face, keyed by its sorted node ids.
    allocate(face_keys(2, 6 * mesh%nzone))
    do z = 1, mesh%nzone
      do f = 1, 6
        face_keys(:, 6 * (z - 1) + f) = &
            sorted_key(int(mesh%connectivity(HEX_FACE_NODES(:, f), z)))
      end do
    end do
    call sort_order(face_keys, face_order)

    allocate(quad_set(data%nquad), quad_face(data%nquad))
    quad_face = 0
    nbad_node = 0
    nbad_face = 0
    do q = 1, data%nquad
      quad_set(q) = find_sorted(set_tags, data%quad_group(q))
      unknown = .false.
      do k = 1, 4
        file_index = find_tag(node_keys, node_order, data%quad_node(k, q))
        if (file_index == 0) then
          unknown = .true.
          call status%add_capped(nbad_node, MAX_REPORT, prefix//'quadrilateral '//i8toa(data%quad_tag(q))// &
              ' refers to node '//i8toa(data%quad_node(k, q))//', which is not in $Nodes')
          nodes(k) = 0
        else
          nodes(k) = new_id(file_index)
        end if
      end do
      if (unknown) cycle
      best = 0
      if (all(nodes > 0)) then
        p = lower_bound(face_keys, face_order, sorted_key(nodes))
        do while (p <= size(face_order))
          candidate = face_order(p)
          if (any(face_keys(:, candidate) /= sorted_key(nodes))) exit
          ! Prefer the face whose outward normal agrees with the quad's orientation.
          if (best == 0) best = candidate
          z = (candidate - 1) / 6 + 1
          f = candidate - 6 * (z - 1)
          if (same_cycle(int(mesh%connectivity(HEX_FACE_NODES(:, f), z)), nodes)) then
            best = candidate
            exit
          end if
          p = p + 1
        end do
      end if
      if (best == 0) then
        call status%add_capped(nbad_face, MAX_REPORT, prefix//'quadrilateral '//i8toa(data%quad_tag(q))// &
            ' of face set '''//trim(set_names(quad_set(q)))//''' matches no hexahedron face')
      else
        quad_face(q) = best
      end if
    end do
    call status%add_more(prefix, nbad_node, MAX_REPORT, 'unknown node tags in quadrilaterals')
    call status%add_more(prefix, nbad_face, MAX_REPORT, 'quadrilaterals matching no hexahedron face')

    ! CSR by set, sorted by (zone, face) within each set, repeats removed.
    mesh%nset = nset
    allocate(mesh%set_name(nset), mesh%set_start(nset + 1))
    mesh%set_name = set_names
    allocate(entry_keys(2, data%nquad))
    do q = 1, data%nquad
      entry_keys(:, q) = [int(quad_set(q), i8), int(quad_face(q), i8)]
    end do
    call sort_order(entry_keys, entry_order)
    allocate(mesh%set_zone(data%nquad), mesh%set_face(data%nquad))
    n = 0
    m = 1
    do s = 1, nset
      mesh%set_start(s) = n + 1
      last = 0
      do while (m <= data%nquad)
        q = entry_order(m)
        if (quad_set(q) /= s) exit
        m = m + 1
        if (quad_face(q) == 0 .or. quad_face(q) == last) cycle
        last = quad_face(q)
        n = n + 1
        mesh%set_zone(n) = int((last - 1) / 6 + 1, ik)
        mesh%set_face(n) = int(last - 6 * (mesh%set_zone(n) - 1), ik)
      end do
    end do
    mesh%set_start(nset + 1) = n + 1
    call shrink(mesh%set_zone, n)
    call shrink(mesh%set_face, n)
  end subroutine build_sets

  !> Keep the first n entries of a.
  subroutine shrink(a, n)
    integer(ik), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer(ik), allocatable :: b(:)
    allocate(b(n))
    b = a(1:n)
    call move_alloc(b, a)
  end subroutine shrink

  !> Column of the one-row keys equal to tag, 0 if none.
  pure integer function find_tag(keys, order, tag) result(column)
    integer(i8), intent(in) :: keys(:, :)
    integer, intent(in) :: order(:)
    integer(i8), intent(in) :: tag
    integer :: p
    column = 0
    p = lower_bound(keys, order, [tag])
    if (p <= size(order)) then
      if (keys(1, order(p)) == tag) column = order(p)
    end if
  end function find_tag

end module mesh_gmsh
