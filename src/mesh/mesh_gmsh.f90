!> Reader of Gmsh ASCII meshes, format 2.2 and 4.1, into a global_mesh_t.
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
  use core_sort, only: sort_order, sort_values
  use core_text, only: itoa => to_text, i8toa => to_text
  use mesh_geometry, only: hex_volume, HEX_FACE_NODES
  use mesh_global, only: global_mesh_t, NAME_LEN
  implicit none
  private
  public :: mesh_read_gmsh

  integer, parameter :: TYPE_QUAD = 3 !< Gmsh 4-node quadrilateral
  integer, parameter :: TYPE_HEX = 5 !< Gmsh 8-node hexahedron
  integer, parameter :: VERSION_22 = 22, VERSION_41 = 41
  !> Per-element problems of one kind reported one by one before a summary line.
  integer, parameter :: MAX_REPORT = 10
  !> Packs two non-negative 32-bit integers into one 64-bit sort key.
  integer(i8), parameter :: SHIFT = 4294967296_i8
  integer, parameter :: CHUNK_LEN = 1024

  !> Line-oriented token reader; the first syntax error is fatal and kept in message.
  type :: reader_t
    integer :: unit = -1 !< open file
    character(len=:), allocatable :: line !< current line
    integer :: pos = 1 !< next character of line to look at
    integer :: line_number = 0 !< of line, for messages
    logical :: eof = .false. !< the file is exhausted
    logical :: failed = .false. !< a fatal problem was found
    character(len=:), allocatable :: message !< what it was
    character(len=:), allocatable :: section !< current $Section, for messages
  end type reader_t

  !> Everything kept from the file, before checking and renumbering.
  type :: gmsh_data_t
    integer :: version = 0 !< VERSION_22 or VERSION_41
    logical :: has_names = .false. !< a $PhysicalNames section was read
    integer :: nname = 0 !< entries of $PhysicalNames
    integer, allocatable :: name_dim(:), name_tag(:)
    character(len=256), allocatable :: name_text(:)
    logical :: has_entities = .false. !< a $Entities section was read (4.1)
    integer :: nentity = 0
    integer(i8), allocatable :: entity_key(:, :) !< (1, n): dim * SHIFT + tag
    integer, allocatable :: entity_order(:) !< sorting permutation of entity_key
    integer, allocatable :: entity_start(:) !< CSR into entity_phys, size nentity + 1
    integer, allocatable :: entity_phys(:) !< physical tags of each entity
    logical :: has_nodes = .false.
    integer :: nnode = 0 !< nodes in the file
    integer(i8), allocatable :: node_tag(:)
    real(rk), allocatable :: node_xyz(:, :) !< (3, nnode)
    logical :: has_elements = .false.
    integer :: nhex = 0
    integer(i8), allocatable :: hex_tag(:), hex_node(:, :) !< node tags (8, nhex)
    integer, allocatable :: hex_group(:) !< 3D physical tag, 0 = none
    integer :: nquad = 0 !< quads in 2D physical groups (one entry per group)
    integer(i8), allocatable :: quad_tag(:), quad_node(:, :) !< node tags (4, nquad)
    integer, allocatable :: quad_group(:) !< 2D physical tag
    integer :: nbad = 0 !< other elements in 2D or 3D physical groups
  end type gmsh_data_t

contains

  !> Read an ASCII Gmsh mesh (.msh 2.2 or 4.1). Every problem goes to status with a
  !> message starting "mesh file '<path>': "; on any problem the mesh is left empty.
  subroutine mesh_read_gmsh(path, mesh, block_names, status)
    character(len=*), intent(in) :: path !< the .msh file
    type(global_mesh_t), intent(inout) :: mesh !< the mesh read; zone_block indexes block_names
    !> Names of the 3D physical groups in order of their physical tags.
    character(len=NAME_LEN), allocatable, intent(out) :: block_names(:)
    type(status_t), intent(inout) :: status !< problems are added here
    type(reader_t) :: r
    type(gmsh_data_t) :: data
    character(len=:), allocatable :: prefix
    character(len=256) :: msg
    logical :: exists
    integer :: ios, count0

    prefix = "mesh file '"//trim(path)//"': "
    count0 = status%count
    call mesh%free()
    allocate(block_names(0))
    inquire(file=path, exist=exists)
    if (.not. exists) then
      call status%add(prefix//'no such file')
      return
    end if
    open(newunit=r%unit, file=path, status='old', action='read', form='formatted', &
        access='sequential', iostat=ios, iomsg=msg)
    if (ios /= 0) then
      call status%add(prefix//'cannot open it: '//trim(msg))
      return
    end if
    r%line = ''
    r%section = ''
    r%message = ''
    call parse_file(r, data, prefix, status)
    close(r%unit)
    if (r%failed) then
      call status%add(prefix//r%message)
    else
      call build_mesh(data, prefix, mesh, block_names, status)
    end if
    if (status%count > count0) then
      call mesh%free()
      if (allocated(block_names)) deallocate(block_names)
      allocate(block_names(0))
    end if
  end subroutine mesh_read_gmsh

  ! ---------------------------------------------------------------------------
  ! Parsing
  ! ---------------------------------------------------------------------------

  !> Read the sections of the file into data; unknown sections are skipped.
  subroutine parse_file(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: i1, i2
    logical :: at_end
    character(len=:), allocatable :: name

    call reader_token(r, i1, i2, at_end)
    if (at_end) then
      call reader_fail(r, 'the file is empty; expected a Gmsh mesh starting with $MeshFormat')
      return
    end if
    if (r%line(i1:i2) /= '$MeshFormat') then
      call reader_fail(r, 'not a Gmsh mesh: expected $MeshFormat, found '''// &
          clip(r%line(i1:i2))//'''')
      return
    end if
    call parse_format(r, data)
    do while (.not. r%failed)
      call reader_token(r, i1, i2, at_end)
      if (at_end .or. r%failed) exit
      name = r%line(i1:i2)
      r%section = name
      select case (name)
      case ('$MeshFormat')
        call reader_fail(r, 'a second $MeshFormat section')
      case ('$PhysicalNames')
        call parse_physical_names(r, data, prefix, status)
      case ('$Entities')
        if (data%version == VERSION_41) then
          call parse_entities(r, data)
        else
          call reader_skip_section(r, name(2:))
        end if
      case ('$PartitionedEntities')
        call reader_fail(r, 'partitioned meshes are not supported; save the mesh '// &
            'unpartitioned (impact3d partitions it itself)')
      case ('$Nodes')
        if (data%has_nodes) then
          call reader_fail(r, 'a second $Nodes section')
        else if (data%version == VERSION_22) then
          call parse_nodes_22(r, data)
        else
          call parse_nodes_41(r, data)
        end if
      case ('$Elements')
        if (data%has_elements) then
          call reader_fail(r, 'a second $Elements section')
        else if (data%version == VERSION_22) then
          call parse_elements_22(r, data, prefix, status)
        else
          call parse_elements_41(r, data, prefix, status)
        end if
      case default
        if (name(1:1) == '$' .and. len(name) > 1) then
          call reader_skip_section(r, name(2:))
        else
          call reader_fail(r, 'unexpected text '''//clip(name)//''' outside any section')
        end if
      end select
      r%section = ''
    end do
    if (r%failed) return
    if (.not. data%has_nodes) then
      call reader_fail(r, 'the file has no $Nodes section')
    else if (.not. data%has_elements) then
      call reader_fail(r, 'the file has no $Elements section')
    end if
  end subroutine parse_file

  !> $MeshFormat: accept ASCII 2.2 and 4.1 only.
  subroutine parse_format(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: i1, i2, file_type, data_size, ios
    real(rk) :: number
    character(len=:), allocatable :: version

    r%section = '$MeshFormat'
    call reader_required_token(r, 'the format version', i1, i2)
    if (r%failed) return
    version = r%line(i1:i2)
    call read_int(r, 'the file type', file_type)
    call read_int(r, 'the data size', data_size)
    if (r%failed) return
    call reader_end_line(r)
    read(version, *, iostat=ios) number
    if (ios /= 0) number = -1.0_rk
    if (abs(number - 2.2_rk) < 1.0e-9_rk) then
      data%version = VERSION_22
    else if (abs(number - 4.1_rk) < 1.0e-9_rk) then
      data%version = VERSION_41
    else
      call reader_fail(r, 'Gmsh format version '//clip(version)//' is not supported; '// &
          'impact3d reads ASCII .msh 2.2 and 4.1 (gmsh -format msh22 or msh41)')
      return
    end if
    if (file_type /= 0) then
      call reader_fail(r, 'the file is binary (format '//clip(version)//', file type '// &
          itoa(file_type)//'); impact3d reads ASCII .msh only (set Mesh.Binary = 0)')
      return
    end if
    call reader_expect(r, '$EndMeshFormat')
  end subroutine parse_format

  !> $PhysicalNames: lines "dim tag "name"".
  subroutine parse_physical_names(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: n, i, j, dim, tag, q1, q2

    if (data%has_names) then
      call reader_fail(r, 'a second $PhysicalNames section')
      return
    end if
    call read_count(r, 'the number of physical names', n)
    if (r%failed) return
    call reader_end_line(r)
    allocate(data%name_dim(n), data%name_tag(n), data%name_text(n))
    do i = 1, n
      call read_int(r, 'a physical dimension', dim)
      call read_int(r, 'a physical tag', tag)
      if (r%failed) return
      q1 = index(r%line(r%pos:), '"')
      q2 = index(r%line(r%pos:), '"', back=.true.)
      if (q1 == 0 .or. q2 <= q1) then
        call reader_fail(r, 'expected a physical name in double quotes')
        return
      end if
      data%name_dim(i) = dim
      data%name_tag(i) = tag
      ! A name longer than the buffer stays longer than NAME_LEN: build_mesh reports it.
      data%name_text(i) = r%line(r%pos + q1:r%pos + q2 - 2)
      do j = 1, i - 1
        if (data%name_dim(j) == dim .and. data%name_tag(j) == tag) then
          call status%add(prefix//'$PhysicalNames names the '//itoa(dim)// &
              'D physical group '//itoa(tag)//' twice')
        end if
      end do
      call reader_end_line(r)
    end do
    data%nname = n
    data%has_names = .true.
    call reader_expect(r, '$EndPhysicalNames')
  end subroutine parse_physical_names

  !> $Entities (4.1): the physical tags of every point, curve, surface and volume.
  subroutine parse_entities(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: counts(0:3), dim, i, k, n, tag, nphys, phys, nskip
    real(rk) :: value

    if (data%has_entities) then
      call reader_fail(r, 'a second $Entities section')
      return
    end if
    do dim = 0, 3
      call read_count(r, 'the number of entities', counts(dim))
    end do
    if (r%failed) return
    call reader_end_line(r)
    data%nentity = sum(counts)
    allocate(data%entity_key(1, data%nentity), data%entity_start(data%nentity + 1))
    allocate(data%entity_phys(16))
    data%entity_start(1) = 1
    n = 0
    do dim = 0, 3
      nskip = 6
      if (dim == 0) nskip = 3
      do i = 1, counts(dim)
        call read_int(r, 'an entity tag', tag)
        do k = 1, nskip
          call read_real(r, 'a coordinate', value)
        end do
        call read_count(r, 'the number of physical tags', nphys)
        if (r%failed) return
        n = n + 1
        data%entity_key(1, n) = int(dim, i8) * SHIFT + int(tag, i8)
        call grow_int(data%entity_phys, data%entity_start(n) - 1 + nphys)
        do k = 1, nphys
          call read_int(r, 'a physical tag', phys)
          data%entity_phys(data%entity_start(n) + k - 1) = phys
        end do
        data%entity_start(n + 1) = data%entity_start(n) + nphys
        call reader_end_line(r)
        if (r%failed) return
      end do
    end do
    call sort_order(data%entity_key, data%entity_order)
    data%has_entities = .true.
    call reader_expect(r, '$EndEntities')
  end subroutine parse_entities

  !> $Nodes in format 2.2: a count, then "tag x y z" lines.
  subroutine parse_nodes_22(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: n, i, k

    call read_count(r, 'the number of nodes', n)
    if (r%failed) return
    call reader_end_line(r)
    call allocate_nodes(r, data, n)
    if (r%failed) return
    do i = 1, n
      call read_i8(r, 'a node tag', data%node_tag(i))
      do k = 1, 3
        call read_real(r, 'a node coordinate', data%node_xyz(k, i))
      end do
      call reader_end_line(r)
      if (r%failed) return
    end do
    data%has_nodes = .true.
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_22

  !> $Nodes in format 4.1: entity blocks of tags followed by coordinates.
  subroutine parse_nodes_41(r, data)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer :: nblock, n, b, i, k, dim, tag, parametric, count, first
    integer(i8) :: min_tag, max_tag

    call read_count(r, 'the number of node blocks', nblock)
    call read_count(r, 'the number of nodes', n)
    call read_i8(r, 'the smallest node tag', min_tag)
    call read_i8(r, 'the largest node tag', max_tag)
    if (r%failed) return
    call reader_end_line(r)
    call allocate_nodes(r, data, n)
    if (r%failed) return
    first = 0
    do b = 1, nblock
      call read_int(r, 'an entity dimension', dim)
      call read_int(r, 'an entity tag', tag)
      call read_int(r, 'the parametric flag', parametric)
      call read_count(r, 'the number of nodes in the block', count)
      if (r%failed) return
      call reader_end_line(r)
      if (first + count > n) then
        call reader_fail(r, 'bad counts: the node blocks hold more than the '//itoa(n)// &
            ' nodes announced in the $Nodes header')
        return
      end if
      do i = first + 1, first + count
        call read_i8(r, 'a node tag', data%node_tag(i))
        call reader_end_line(r)
        if (r%failed) return
        if (data%node_tag(i) < min_tag .or. data%node_tag(i) > max_tag) then
          call reader_fail(r, 'bad counts: node tag '//i8toa(data%node_tag(i))// &
              ' is outside the range '//i8toa(min_tag)//'..'//i8toa(max_tag)// &
              ' given in the $Nodes header')
          return
        end if
      end do
      do i = first + 1, first + count
        do k = 1, 3
          call read_real(r, 'a node coordinate', data%node_xyz(k, i))
        end do
        ! Parametric coordinates, if any, follow on the same line.
        call reader_end_line(r)
        if (r%failed) return
      end do
      first = first + count
    end do
    if (first /= n) then
      call reader_fail(r, 'bad counts: the node blocks hold '//itoa(first)// &
          ' nodes but the $Nodes header announces '//itoa(n))
      return
    end if
    data%has_nodes = .true.
    call reader_expect(r, '$EndNodes')
  end subroutine parse_nodes_41

  !> $Elements in format 2.2: "tag type ntags tags... nodes..." lines.
  subroutine parse_elements_22(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: n, i, k, element_type, ntags, phys, value
    integer(i8) :: tag, nodes(8)

    call read_count(r, 'the number of elements', n)
    if (r%failed) return
    call reader_end_line(r)
    do i = 1, n
      call read_i8(r, 'an element tag', tag)
      call read_int(r, 'an element type', element_type)
      call read_count(r, 'the number of element tags', ntags)
      if (r%failed) return
      phys = 0
      do k = 1, ntags
        call read_int(r, 'an element tag', value)
        if (k == 1) phys = value
      end do
      select case (element_type)
      case (TYPE_HEX)
        do k = 1, 8
          call read_i8(r, 'a node tag', nodes(k))
        end do
        if (r%failed) return
        call add_hex(data, tag, nodes, phys)
      case (TYPE_QUAD)
        do k = 1, 4
          call read_i8(r, 'a node tag', nodes(k))
        end do
        if (r%failed) return
        if (phys /= 0) call add_quad(data, tag, nodes(1:4), phys)
      case default
        if (phys /= 0) then
          if (element_dimension(element_type) < 0) then
            call status%add(prefix//'element '//i8toa(tag)//' has the unknown type '// &
                itoa(element_type)//' and is in physical group '//itoa(phys))
          else if (element_dimension(element_type) >= 2) then
            call report_bad_element(data, prefix, status, tag, element_type, &
                element_dimension(element_type), phys)
          end if
        end if
      end select
      call reader_end_line(r)
      if (r%failed) return
    end do
    data%has_elements = .true.
    call reader_expect(r, '$EndElements')
    call report_bad_summary(data, prefix, status)
  end subroutine parse_elements_22

  !> $Elements in format 4.1: entity blocks of "tag nodes..." lines.
  subroutine parse_elements_41(r, data, prefix, status)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer :: nblock, n, b, i, k, p, dim, entity, element_type, count, total
    integer :: first_phys, last_phys, phys
    integer(i8) :: min_tag, max_tag, tag, nodes(8)

    call read_count(r, 'the number of element blocks', nblock)
    call read_count(r, 'the number of elements', n)
    call read_i8(r, 'the smallest element tag', min_tag)
    call read_i8(r, 'the largest element tag', max_tag)
    if (r%failed) return
    call reader_end_line(r)
    total = 0
    do b = 1, nblock
      call read_int(r, 'an entity dimension', dim)
      call read_int(r, 'an entity tag', entity)
      call read_int(r, 'an element type', element_type)
      call read_count(r, 'the number of elements in the block', count)
      if (r%failed) return
      call reader_end_line(r)
      if (count > n - total) then
        call reader_fail(r, 'bad counts: the element blocks hold more than the '// &
            itoa(n)//' elements announced in the $Elements header')
        return
      end if
      total = total + count
      first_phys = 1
      last_phys = 0
      if (dim >= 2) then
        call entity_physicals(r, data, dim, entity, first_phys, last_phys)
        if (r%failed) return
      end if
      if ((element_type == TYPE_HEX .and. dim /= 3) .or. &
          (element_type == TYPE_QUAD .and. dim /= 2)) then
        call reader_fail(r, 'element type '//itoa(element_type)//' in an entity of dimension '// &
            itoa(dim))
        return
      end if
      if (element_type == TYPE_HEX .and. last_phys > first_phys) then
        call status%add(prefix//'volume '//itoa(entity)//' is in several 3D physical '// &
            'groups; a hexahedron can belong to one block only')
      end if
      if (element_type == TYPE_HEX) call reserve_hex(data, data%nhex + count)
      if (element_type == TYPE_QUAD) then
        call reserve_quad(data, data%nquad + count * (last_phys - first_phys + 1))
      end if
      do i = 1, count
        call read_i8(r, 'an element tag', tag)
        if (r%failed) return
        if (tag < min_tag .or. tag > max_tag) then
          call reader_fail(r, 'bad counts: element tag '//i8toa(tag)// &
              ' is outside the range '//i8toa(min_tag)//'..'//i8toa(max_tag)// &
              ' given in the $Elements header')
          return
        end if
        if (element_type == TYPE_HEX) then
          do k = 1, 8
            call read_i8(r, 'a node tag', nodes(k))
          end do
          if (r%failed) return
          phys = 0
          if (last_phys >= first_phys) phys = data%entity_phys(first_phys)
          call add_hex(data, tag, nodes, phys)
        else if (element_type == TYPE_QUAD) then
          do k = 1, 4
            call read_i8(r, 'a node tag', nodes(k))
          end do
          if (r%failed) return
          do p = first_phys, last_phys
            call add_quad(data, tag, nodes(1:4), data%entity_phys(p))
          end do
        else if (last_phys >= first_phys) then
          call report_bad_element(data, prefix, status, tag, element_type, dim, &
              data%entity_phys(first_phys))
        end if
        call reader_end_line(r)
        if (r%failed) return
      end do
    end do
    if (total /= n) then
      call reader_fail(r, 'bad counts: the element blocks hold '//itoa(total)// &
          ' elements but the $Elements header announces '//itoa(n))
      return
    end if
    data%has_elements = .true.
    call reader_expect(r, '$EndElements')
    call report_bad_summary(data, prefix, status)
  end subroutine parse_elements_41

  !> Range of data%entity_phys holding the physical tags of entity (dim, tag).
  subroutine entity_physicals(r, data, dim, tag, first, last)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(in) :: data
    integer, intent(in) :: dim, tag
    integer, intent(out) :: first, last
    integer :: p, e

    first = 1
    last = 0
    if (.not. data%has_entities) then
      call reader_fail(r, 'elements refer to entities but the file has no $Entities section')
      return
    end if
    p = lower_bound(data%entity_key, data%entity_order, [int(dim, i8) * SHIFT + int(tag, i8)])
    if (p > data%nentity) then
      e = 0
    else
      e = data%entity_order(p)
      if (data%entity_key(1, e) /= int(dim, i8) * SHIFT + int(tag, i8)) e = 0
    end if
    if (e == 0) then
      call reader_fail(r, 'elements refer to the '//itoa(dim)//'D entity '//itoa(tag)// &
          ', which is not in $Entities')
      return
    end if
    first = data%entity_start(e)
    last = data%entity_start(e + 1) - 1
  end subroutine entity_physicals

  !> A non-hexahedron in a 3D group, or a non-quadrilateral in a 2D group.
  subroutine report_bad_element(data, prefix, status, tag, element_type, dim, phys)
    type(gmsh_data_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    integer(i8), intent(in) :: tag
    integer, intent(in) :: element_type, dim, phys

    data%nbad = data%nbad + 1
    if (data%nbad > MAX_REPORT) return
    if (dim == 3) then
      call status%add(prefix//'element '//i8toa(tag)//' of type '//itoa(element_type)// &
          ' is in the 3D physical group '//group_label(data, 3, phys)// &
          ', but impact3d needs hexahedra (8-node, Gmsh type 5): use Recombine'// &
          ' and Transfinite or Extrude with Layers')
    else
      call status%add(prefix//'element '//i8toa(tag)//' of type '//itoa(element_type)// &
          ' is in the 2D physical group '//group_label(data, 2, phys)// &
          ', but face sets need 4-node quadrilaterals (Gmsh type 3)')
    end if
  end subroutine report_bad_element

  !> The count of bad elements beyond those reported one by one.
  subroutine report_bad_summary(data, prefix, status)
    type(gmsh_data_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    type(status_t), intent(inout) :: status
    if (data%nbad > MAX_REPORT) then
      call status%add(prefix//itoa(data%nbad - MAX_REPORT)//' more elements of the wrong'// &
          ' type in 2D or 3D physical groups')
    end if
  end subroutine report_bad_summary

  !> 'name' (tag N) of a physical group if it is named, else "tag N".
  function group_label(data, dim, tag) result(label)
    type(gmsh_data_t), intent(in) :: data
    integer, intent(in) :: dim, tag
    character(len=:), allocatable :: label
    integer :: i
    label = itoa(tag)
    do i = 1, data%nname
      if (data%name_dim(i) == dim .and. data%name_tag(i) == tag) then
        label = ''''//trim(data%name_text(i))//''' (tag '//itoa(tag)//')'
        return
      end if
    end do
  end function group_label

  !> Room for n nodes.
  subroutine allocate_nodes(r, data, n)
    type(reader_t), intent(inout) :: r
    type(gmsh_data_t), intent(inout) :: data
    integer, intent(in) :: n
    integer :: stat
    allocate(data%node_tag(n), data%node_xyz(3, n), stat=stat)
    if (stat /= 0) call reader_fail(r, 'bad counts: cannot allocate '//itoa(n)//' nodes')
    data%nnode = n
  end subroutine allocate_nodes

  !> Room for at least n hexahedra.
  subroutine reserve_hex(data, n)
    type(gmsh_data_t), intent(inout) :: data
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
    type(gmsh_data_t), intent(inout) :: data
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
  subroutine add_hex(data, tag, nodes, phys)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(8)
    integer, intent(in) :: phys
    call reserve_hex(data, data%nhex + 1)
    data%nhex = data%nhex + 1
    data%hex_tag(data%nhex) = tag
    data%hex_node(:, data%nhex) = nodes
    data%hex_group(data%nhex) = phys
  end subroutine add_hex

  !> Append one quadrilateral of the 2D group phys.
  subroutine add_quad(data, tag, nodes, phys)
    type(gmsh_data_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(4)
    integer, intent(in) :: phys
    call reserve_quad(data, data%nquad + 1)
    data%nquad = data%nquad + 1
    data%quad_tag(data%nquad) = tag
    data%quad_node(:, data%nquad) = nodes
    data%quad_group(data%nquad) = phys
  end subroutine add_quad

  !> Make a(:) hold at least n entries, keeping its contents.
  subroutine grow_int(a, n)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer, allocatable :: b(:)
    if (size(a) >= n) return
    allocate(b(max(n, 2 * size(a))))
    b(1:size(a)) = a
    call move_alloc(b, a)
  end subroutine grow_int

  !> Dimension of a Gmsh element type, -1 if unknown.
  pure integer function element_dimension(element_type) result(dim)
    integer, intent(in) :: element_type
    select case (element_type)
    case (15)
      dim = 0
    case (1, 8, 26:28, 62:67, 70, 84)
      dim = 1
    case (2, 3, 9, 10, 16, 20:25, 34, 36:61, 68, 69, 85, 86)
      dim = 2
    case (4:7, 11:14, 17:19, 29:33, 35, 71:75, 79:83, 87:93)
      dim = 3
    case default
      dim = -1
    end select
  end function element_dimension

  ! ---------------------------------------------------------------------------
  ! Building the mesh
  ! ---------------------------------------------------------------------------

  !> Check what was read, renumber the nodes, match quads to hex faces, fill mesh.
  subroutine build_mesh(data, prefix, mesh, block_names, status)
    type(gmsh_data_t), intent(inout) :: data
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
    if (data%nhex == 0) then
      call status%add(prefix//'no 8-node hexahedra (Gmsh type 5) found; impact3d needs '// &
          'a hexahedral mesh (Recombine with Transfinite, or Extrude with Layers)')
      return
    end if

    ! Blocks and face sets.
    call group_tags(data, 3, data%hex_group(1:data%nhex), block_tags)
    call group_tags(data, 2, data%quad_group(1:data%nquad), set_tags)
    if (data%version == VERSION_41 .and. .not. data%has_names .and. &
        size(block_tags) + size(set_tags) > 0) then
      call status%add(prefix//'physical groups are used but the file has no '// &
          '$PhysicalNames section: name every 2D and 3D physical group '// &
          '(e.g. Physical Volume("steel") = {...};)')
    end if
    call group_names(data, prefix, 3, block_tags, block_names, status)
    call group_names(data, prefix, 2, set_tags, set_names, status)

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
    type(gmsh_data_t), intent(in) :: data
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

  !> Sorted distinct physical tags of dimension dim: named ones and those used.
  subroutine group_tags(data, dim, used, tags)
    type(gmsh_data_t), intent(in) :: data
    integer, intent(in) :: dim
    integer, intent(in) :: used(:) !< tags of elements, 0 = none
    integer, allocatable, intent(out) :: tags(:)
    integer(i8), allocatable :: keys(:, :)
    integer, allocatable :: order(:)
    integer :: n, i, m

    n = 0
    allocate(keys(1, size(used) + data%nname))
    do i = 1, size(used)
      if (used(i) /= 0) then
        n = n + 1
        keys(1, n) = used(i)
      end if
    end do
    do i = 1, data%nname
      if (data%name_dim(i) == dim) then
        n = n + 1
        keys(1, n) = data%name_tag(i)
      end if
    end do
    call sort_order(keys(:, 1:n), order)
    allocate(tags(n))
    m = 0
    do i = 1, n
      if (m > 0) then
        if (tags(m) == keys(1, order(i))) cycle
      end if
      m = m + 1
      tags(m) = int(keys(1, order(i)))
    end do
    tags = tags(1:m)
  end subroutine group_tags

  !> Names of the groups (dim, tags(:)); unnamed 2.2 groups become 'physical_N'.
  subroutine group_names(data, prefix, dim, tags, names, status)
    type(gmsh_data_t), intent(in) :: data
    character(len=*), intent(in) :: prefix
    integer, intent(in) :: dim, tags(:)
    character(len=NAME_LEN), allocatable, intent(inout) :: names(:)
    type(status_t), intent(inout) :: status
    character(len=256) :: name
    integer :: i, j, k
    logical :: found

    if (allocated(names)) deallocate(names)
    allocate(names(size(tags)))
    do i = 1, size(tags)
      found = .false.
      do j = 1, data%nname
        if (data%name_dim(j) == dim .and. data%name_tag(j) == tags(i)) then
          found = .true.
          name = data%name_text(j)
          exit
        end if
      end do
      if (.not. found) then
        name = 'physical_'//itoa(tags(i))
        ! Without any $PhysicalNames, build_mesh has said so once.
        if (data%version == VERSION_41 .and. data%has_names) then
          call status%add(prefix//'the '//itoa(dim)//'D physical group '//itoa(tags(i))// &
              ' has no name in $PhysicalNames')
        end if
      end if
      if (len_trim(name) == 0) then
        call status%add(prefix//'the '//itoa(dim)//'D physical group '//itoa(tags(i))// &
            ' has an empty name')
      else if (len_trim(name) > NAME_LEN) then
        call status%add(prefix//'the name '''//trim(name)//''' of the '//itoa(dim)// &
            'D physical group '//itoa(tags(i))//' is longer than '//itoa(NAME_LEN)// &
            ' characters')
      end if
      names(i) = name(1:NAME_LEN)
      do k = 1, i - 1
        if (names(k) == names(i) .and. len_trim(name) > 0) then
          call status%add(prefix//'the '//itoa(dim)//'D physical groups '//itoa(tags(k))// &
              ' and '//itoa(tags(i))//' have the same name '''//trim(names(i))//'''')
        end if
      end do
    end do
  end subroutine group_names

  !> Sort key of a face or element: its node ids (an even number of them, each
  !> in 0..2**31-1) in increasing order, packed two by two.
  pure function sorted_key(nodes) result(key)
    integer, intent(in) :: nodes(:)
    integer(i8) :: key(size(nodes) / 2)
    integer :: s(size(nodes)), i
    s = nodes
    call sort_values(s)
    do i = 1, size(key)
      key(i) = int(s(2 * i - 1), i8) * SHIFT + int(s(2 * i), i8)
    end do
  end function sorted_key

  !> True if b lists the nodes of a in the same cyclic order (same orientation).
  pure logical function same_cycle(a, b)
    integer, intent(in) :: a(4), b(4)
    integer :: shift_by, k
    same_cycle = .false.
    do shift_by = 0, 3
      if (a(1 + shift_by) /= b(1)) cycle
      same_cycle = .true.
      do k = 1, 3
        if (a(1 + modulo(shift_by + k, 4)) /= b(1 + k)) same_cycle = .false.
      end do
      return
    end do
  end function same_cycle

  ! ---------------------------------------------------------------------------
  ! Sorting and searching
  ! ---------------------------------------------------------------------------

  !> First position p in order with keys(:, order(p)) >= key; size(order) + 1 if none.
  pure integer function lower_bound(keys, order, key) result(lo)
    integer(i8), intent(in) :: keys(:, :)
    integer, intent(in) :: order(:)
    integer(i8), intent(in) :: key(:)
    integer :: hi, mid, i
    logical :: less
    lo = 1
    hi = size(order) + 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      less = .false.
      do i = 1, size(key)
        if (keys(i, order(mid)) /= key(i)) then
          less = keys(i, order(mid)) < key(i)
          exit
        end if
      end do
      if (less) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
  end function lower_bound

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

  !> Position of value in the sorted list, 0 if absent.
  pure integer function find_sorted(list, value) result(position)
    integer, intent(in) :: list(:), value
    integer :: lo, hi, mid
    position = 0
    lo = 1
    hi = size(list)
    do while (lo <= hi)
      mid = (lo + hi) / 2
      if (list(mid) == value) then
        position = mid
        return
      else if (list(mid) < value) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function find_sorted

  ! ---------------------------------------------------------------------------
  ! Token reader
  ! ---------------------------------------------------------------------------

  !> Record the first fatal problem, with the line number and section.
  subroutine reader_fail(r, text)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: text
    if (r%failed) return
    r%failed = .true.
    if (len(r%section) > 0) then
      r%message = 'line '//itoa(r%line_number)//' (in '//r%section//'): '//text
    else
      r%message = 'line '//itoa(r%line_number)//': '//text
    end if
  end subroutine reader_fail

  !> Read the next line, of any length, without its line terminator.
  subroutine reader_next_line(r)
    type(reader_t), intent(inout) :: r
    character(len=CHUNK_LEN) :: chunk
    character(len=256) :: msg
    integer :: ios, nread
    r%line = ''
    r%pos = 1
    if (r%eof) return
    do
      read(r%unit, '(a)', advance='no', size=nread, iostat=ios, iomsg=msg) chunk
      if (ios == 0) then
        r%line = r%line//chunk
      else if (is_iostat_eor(ios)) then
        r%line = r%line//chunk(1:nread)
        exit
      else if (is_iostat_end(ios)) then
        r%line = r%line//chunk(1:nread)
        if (len(r%line) == 0) r%eof = .true.
        exit
      else
        r%line_number = r%line_number + 1
        call reader_fail(r, 'cannot read: '//trim(msg))
        r%eof = .true.
        return
      end if
    end do
    if (.not. r%eof) r%line_number = r%line_number + 1
    if (len(r%line) > 0) then
      if (r%line(len(r%line):) == achar(13)) r%line = r%line(1:len(r%line) - 1)
    end if
  end subroutine reader_next_line

  !> Next whitespace-separated token as r%line(first:last); at_end at the end of the file.
  subroutine reader_token(r, first, last, at_end)
    type(reader_t), intent(inout) :: r
    integer, intent(out) :: first, last
    logical, intent(out) :: at_end
    first = 1
    last = 0
    at_end = .false.
    do
      if (r%failed) return
      do while (r%pos <= len(r%line))
        if (.not. is_blank(r%line(r%pos:r%pos))) exit
        r%pos = r%pos + 1
      end do
      if (r%pos <= len(r%line)) exit
      call reader_next_line(r)
      if (r%eof) then
        at_end = .true.
        return
      end if
    end do
    first = r%pos
    do while (r%pos <= len(r%line))
      if (is_blank(r%line(r%pos:r%pos))) exit
      r%pos = r%pos + 1
    end do
    last = r%pos - 1
  end subroutine reader_token

  !> Next token, which must exist: the end of the file here means truncation.
  subroutine reader_required_token(r, what, first, last)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer, intent(out) :: first, last
    logical :: at_end
    call reader_token(r, first, last, at_end)
    if (at_end) call reader_fail(r, 'unexpected end of file while reading '//what// &
        ': the file is truncated or a count is too large')
  end subroutine reader_required_token

  !> Drop the rest of the current line.
  subroutine reader_end_line(r)
    type(reader_t), intent(inout) :: r
    r%pos = len(r%line) + 1
  end subroutine reader_end_line

  !> The next token must be text (a section end).
  subroutine reader_expect(r, text)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: text
    integer :: i1, i2
    call reader_required_token(r, text, i1, i2)
    if (r%failed) return
    if (r%line(i1:i2) /= text) then
      call reader_fail(r, 'bad counts: expected '//text//' but found '''// &
          clip(r%line(i1:i2))//''' (the section holds more entries than its header says)')
    end if
  end subroutine reader_expect

  !> Skip an unknown section up to its $End line.
  subroutine reader_skip_section(r, name)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: name !< without the $
    do
      call reader_next_line(r)
      if (r%failed) return
      if (r%eof) then
        call reader_fail(r, 'unexpected end of file: section $'//name//' is not closed')
        return
      end if
      if (trim(adjustl(r%line)) == '$End'//name) exit
    end do
    call reader_end_line(r)
  end subroutine reader_skip_section

  !> Next token as a 64-bit integer.
  subroutine read_i8(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer(i8), intent(out) :: value
    integer :: i1, i2
    logical :: ok
    value = 0
    call reader_required_token(r, what, i1, i2)
    if (r%failed) return
    call parse_i8(r%line(i1:i2), value, ok)
    if (.not. ok) call reader_fail(r, 'expected '//what//' (an integer), found '''// &
        clip(r%line(i1:i2))//'''')
  end subroutine read_i8

  !> Next token as a default integer.
  subroutine read_int(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer, intent(out) :: value
    integer(i8) :: big
    value = 0
    call read_i8(r, what, big)
    if (r%failed) return
    if (abs(big) > int(huge(value), i8)) then
      call reader_fail(r, what//' '//i8toa(big)//' is too large')
      return
    end if
    value = int(big)
  end subroutine read_int

  !> A count: an integer >= 0.
  subroutine read_count(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    integer, intent(out) :: value
    call read_int(r, what, value)
    if (r%failed) return
    if (value < 0) call reader_fail(r, 'bad counts: '//what//' is negative ('//itoa(value)//')')
  end subroutine read_count

  !> Next token as a real number.
  subroutine read_real(r, what, value)
    type(reader_t), intent(inout) :: r
    character(len=*), intent(in) :: what
    real(rk), intent(out) :: value
    integer :: i1, i2, ios
    value = 0.0_rk
    call reader_required_token(r, what, i1, i2)
    if (r%failed) return
    ios = 1
    if (verify(r%line(i1:i2), '0123456789+-.eEdD') == 0) then
      read(r%line(i1:i2), *, iostat=ios) value
    end if
    if (ios /= 0) call reader_fail(r, 'expected '//what//' (a number), found '''// &
        clip(r%line(i1:i2))//'''')
  end subroutine read_real

  !> Decimal integer with an optional sign; ok false on anything else or overflow.
  pure subroutine parse_i8(text, value, ok)
    character(len=*), intent(in) :: text
    integer(i8), intent(out) :: value
    logical, intent(out) :: ok
    integer :: i, start, digit
    logical :: negative
    value = 0
    ok = .false.
    if (len(text) == 0) return
    negative = text(1:1) == '-'
    start = 1
    if (text(1:1) == '-' .or. text(1:1) == '+') start = 2
    if (start > len(text)) return
    do i = start, len(text)
      digit = iachar(text(i:i)) - iachar('0')
      if (digit < 0 .or. digit > 9) return
      if (value > (huge(value) - digit) / 10) return
      value = 10 * value + digit
    end do
    if (negative) value = -value
    ok = .true.
  end subroutine parse_i8

  !> Space or tab.
  pure logical function is_blank(c)
    character, intent(in) :: c
    is_blank = c == ' ' .or. c == achar(9)
  end function is_blank

  !> At most 40 characters of text, for messages.
  pure function clip(text) result(short)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: short
    if (len(text) > 40) then
      short = text(1:40)//'...'
    else
      short = text
    end if
  end function clip

end module mesh_gmsh
