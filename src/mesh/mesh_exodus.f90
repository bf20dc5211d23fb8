!> Reader of Exodus II meshes (Cubit/Trelis, SEACAS, meshio, ...) into a
!> global_mesh_t, through the Exodus II C library (Debian libexodusii-dev) and
!> the thin C layer mesh_exodus_c.c.
!>
!> Zones are the elements of the element blocks, which must all be 8-node
!> hexahedra (HEX8, also written HEX or HEXAHEDRON); the element blocks, in
!> file order, are the blocks of the mesh, named by the file's block names
!> ('block_<id>' for a block without a name). Side sets become face sets
!> (named the same way, 'sideset_<id>' without a name); Exodus side s of a
!> hexahedron is the mesh_geometry face EXODUS_SIDE_FACE(s). Node sets are
!> ignored. Nodes used by the hexahedra are renumbered 1..nnode in file
!> order; zones keep the file's element order (the order side sets count in).
!> Exodus's HEX8 node order is the VTK order used by mesh_geometry.
module mesh_exodus
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_float, c_char, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_text, only: itoa => to_text
  use core_sort, only: sort_order, sort_unique, sorted_find
  use mesh_geometry, only: hex_volume, quad_vector_area, HEX_FACE_NODES
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_range, only: mesh_range_t, range_grow_faces
  use mesh_report, only: merge_capped, MAX_REPORT, LINE_LEN
  use parallel_env, only: par_rank, par_size, par_sum, par_max
  use parallel_route, only: par_block_range, par_block_owner, par_route, par_route_free, &
      par_exscan_i8, par_allgather_text, par_route_rounds, par_ordered_sum
  implicit none
  private
  public :: mesh_read_exodus, exodus_scan, range_add_exodus

  !> mesh_geometry face of Exodus side 1..6 (sides 1-4 the faces through edges
  !> 1-2, 2-3, 3-4, 4-1 of the bottom, 5 the bottom 1-4-3-2, 6 the top 5-6-7-8).
  integer, parameter, public :: EXODUS_SIDE_FACE(6) = [3, 4, 5, 6, 1, 2]
  integer, parameter :: KIND_BLOCK = 1, KIND_SIDE_SET = 3
  integer, parameter :: TEXT_LEN = 257
  !> Items per read and per all-to-all when every rank reads its ranges.
  integer, parameter :: CHUNK = 65536

  !> An Exodus II file read by ranges on every rank (exodus_scan, then
  !> range_add_exodus): its sizes and names, the same on every rank, and
  !> this rank's block of the file's nodes with the ids they get (the nodes
  !> used by the hexahedra numbered 1, 2, ... in file order, 0 = unused).
  type, public :: exodus_part_t
    character(len=:), allocatable :: path
    integer :: nnode_file = 0 !< nodes in the file
    integer :: nelem = 0 !< elements (= zones)
    integer :: nblock = 0, nset = 0 !< element blocks, side sets
    integer(c_int), allocatable :: block_id(:), set_id(:)
    character(len=NAME_LEN), allocatable :: block_names(:), set_names(:)
    integer, allocatable :: block_start(:) !< (nblock + 1) elements before each block
    integer(i8), allocatable :: set_size(:) !< entries of each side set
    integer(i8) :: nnode = 0 !< nodes used by the hexahedra
    integer(i8) :: node_first = 1 !< first file node of this rank's block
    integer :: node_count = 0 !< file nodes in this rank's block
    integer(i8), allocatable :: node_id(:) !< (node_count) their ids (0 = unused)
  end type exodus_part_t

  interface
    integer(c_int) function exo_open(path, exoid, version) bind(C, name='impact3d_exo_open')
      import :: c_int, c_char, c_float
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: exoid
      real(c_float), intent(out) :: version
    end function exo_open
    integer(c_int) function exo_close(exoid) bind(C, name='impact3d_exo_close')
      import :: c_int
      integer(c_int), value :: exoid
    end function exo_close
    integer(c_int) function exo_init(exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset) &
        bind(C, name='impact3d_exo_init')
      import :: c_int
      integer(c_int), value :: exoid
      integer(c_int), intent(out) :: ndim, nnode, nelem, nblock, nnodeset, nsideset
    end function exo_init
    integer(c_int) function exo_coord(exoid, x, y, z) bind(C, name='impact3d_exo_coord')
      import :: c_int, c_double
      integer(c_int), value :: exoid
      real(c_double), intent(out) :: x(*), y(*), z(*)
    end function exo_coord
    integer(c_int) function exo_ids(exoid, kind, ids) bind(C, name='impact3d_exo_ids')
      import :: c_int
      integer(c_int), value :: exoid, kind
      integer(c_int), intent(out) :: ids(*)
    end function exo_ids
    integer(c_int) function exo_name(exoid, kind, id, name, length) &
        bind(C, name='impact3d_exo_name')
      import :: c_int, c_char
      integer(c_int), value :: exoid, kind, id, length
      character(kind=c_char), intent(out) :: name(*)
    end function exo_name
    integer(c_int) function exo_block(exoid, id, type, length, nelem, nper) &
        bind(C, name='impact3d_exo_block')
      import :: c_int, c_char
      integer(c_int), value :: exoid, id, length
      character(kind=c_char), intent(out) :: type(*)
      integer(c_int), intent(out) :: nelem, nper
    end function exo_block
    integer(c_int) function exo_conn(exoid, id, conn) bind(C, name='impact3d_exo_conn')
      import :: c_int
      integer(c_int), value :: exoid, id
      integer(c_int), intent(out) :: conn(*)
    end function exo_conn
    integer(c_int) function exo_side_set_size(exoid, id, nside) &
        bind(C, name='impact3d_exo_side_set_size')
      import :: c_int
      integer(c_int), value :: exoid, id
      integer(c_int), intent(out) :: nside
    end function exo_side_set_size
    integer(c_int) function exo_side_set(exoid, id, elem, side) &
        bind(C, name='impact3d_exo_side_set')
      import :: c_int
      integer(c_int), value :: exoid, id
      integer(c_int), intent(out) :: elem(*), side(*)
    end function exo_side_set
    integer(c_int) function exo_partial_coord(exoid, start, n, x, y, z) &
        bind(C, name='impact3d_exo_partial_coord')
      import :: c_int, c_double
      integer(c_int), value :: exoid, start, n
      real(c_double), intent(out) :: x(*), y(*), z(*)
    end function exo_partial_coord
    integer(c_int) function exo_partial_conn(exoid, id, start, n, conn) &
        bind(C, name='impact3d_exo_partial_conn')
      import :: c_int
      integer(c_int), value :: exoid, id, start, n
      integer(c_int), intent(out) :: conn(*)
    end function exo_partial_conn
    integer(c_int) function exo_partial_side_set(exoid, id, start, n, elem, side) &
        bind(C, name='impact3d_exo_partial_side_set')
      import :: c_int
      integer(c_int), value :: exoid, id, start, n
      integer(c_int), intent(out) :: elem(*), side(*)
    end function exo_partial_side_set
  end interface

contains

  !> Read an Exodus II file. Every problem goes to status with a message
  !> starting "mesh file '<path>': "; on any problem the mesh is left empty.
  subroutine mesh_read_exodus(path, mesh, block_names, status)
    character(len=*), intent(in) :: path !< the Exodus II file (full path)
    type(global_mesh_t), intent(inout) :: mesh !< the mesh read; zone_block indexes block_names
    !> Names of the element blocks in file order.
    character(len=NAME_LEN), allocatable, intent(out) :: block_names(:)
    type(status_t), intent(inout) :: status !< problems are added here
    character(len=:), allocatable :: prefix
    logical :: exists
    integer(c_int) :: exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset
    real(c_float) :: version
    integer :: count0

    prefix = "mesh file '"//trim(path)//"': "
    count0 = status%count
    call mesh%free()
    allocate(block_names(0))
    inquire(file=path, exist=exists)
    if (.not. exists) then
      call status%add(prefix//'no such file')
      return
    end if
    if (exo_open(trim(path)//c_null_char, exoid, version) /= 0) then
      call status%add(prefix//'cannot open it as an Exodus II file (the Exodus II library '// &
          'could not read it: not a netCDF file, or damaged)')
      return
    end if
    if (exo_init(exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset) /= 0) then
      call status%add(prefix//'cannot read its sizes (ex_get_init failed)')
    else if (ndim /= 3) then
      call status%add(prefix//'the mesh is '//itoa(int(ndim))//'D; impact3d reads 3D meshes')
    else if (nblock < 1 .or. nelem < 1) then
      call status%add(prefix//'the file has no element block (no elements)')
    else
      call read_mesh(exoid, prefix, int(nnode), int(nelem), int(nblock), int(nsideset), mesh, &
          block_names, status)
    end if
    if (exo_close(exoid) /= 0) call status%add(prefix//'cannot close it (ex_close failed)')
    if (status%count > count0) then
      call mesh%free()
      if (allocated(block_names)) deallocate(block_names)
      allocate(block_names(0))
    end if
  end subroutine mesh_read_exodus

  !> Everything after the sizes: coordinates, blocks, side sets, checks.
  subroutine read_mesh(exoid, prefix, nnode, nelem, nblock, nsideset, mesh, block_names, status)
    integer(c_int), intent(in) :: exoid
    character(len=*), intent(in) :: prefix
    integer, intent(in) :: nnode, nelem, nblock, nsideset
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(inout) :: block_names(:)
    type(status_t), intent(inout) :: status
    real(c_double), allocatable :: xc(:), yc(:), zc(:)
    integer(c_int), allocatable :: ids(:), conn(:), elem(:), side(:)
    integer(c_int) :: n_in_block, nper, nside
    integer, allocatable :: new_id(:), conn_all(:, :), zone_of_block(:)
    character(len=TEXT_LEN) :: type_text
    character(len=NAME_LEN), allocatable :: set_names(:)
    integer :: b, e, k, z, n, nbad, count0, s, nface
    logical :: bad_node

    count0 = status%count
    allocate(xc(nnode), yc(nnode), zc(nnode))
    if (exo_coord(exoid, xc, yc, zc) /= 0) then
      call status%add(prefix//'cannot read the node coordinates (ex_get_coord failed)')
      return
    end if
    nbad = 0
    do n = 1, nnode
      if (.not. (ieee_is_finite(xc(n)) .and. ieee_is_finite(yc(n)) .and. ieee_is_finite(zc(n)))) &
          call status%add_capped(nbad, MAX_REPORT, prefix//'node '//itoa(n)//' has a coordinate that is '// &
          'not a finite number')
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'nodes with non-finite coordinates')

    ! Element blocks: names, types, connectivity.
    if (allocated(block_names)) deallocate(block_names)
    allocate(ids(nblock), block_names(nblock), zone_of_block(nelem), conn_all(8, nelem))
    if (exo_ids(exoid, KIND_BLOCK, ids) /= 0) then
      call status%add(prefix//'cannot read the element block ids (ex_get_ids failed)')
      return
    end if
    call entity_names(exoid, KIND_BLOCK, ids, 'block_', 'element block', prefix, block_names, &
        status)
    e = 0
    bad_node = .false.
    do b = 1, nblock
      if (exo_block(exoid, ids(b), type_text, len(type_text, c_int), n_in_block, nper) /= 0) then
        call status%add(prefix//'cannot read element block '''//trim(block_names(b))// &
            ''' (id '//itoa(int(ids(b)))//'): ex_get_block failed')
        return
      end if
      type_text = c_text(type_text)
      if (.not. is_hex8(type_text, int(nper))) then
        call status%add(prefix//'element block '''//trim(block_names(b))//''' (id '// &
            itoa(int(ids(b)))//') holds '//itoa(int(n_in_block))//' elements of type '''// &
            trim(type_text)//''' with '//itoa(int(nper))//' nodes; impact3d reads 8-node '// &
            'hexahedra (HEX8) only')
        cycle
      end if
      if (e + n_in_block > nelem) then
        call status%add(prefix//'the element blocks hold more elements than the file''s '// &
            'element count '//itoa(nelem))
        return
      end if
      if (n_in_block == 0) cycle
      allocate(conn(8 * n_in_block))
      if (exo_conn(exoid, ids(b), conn) /= 0) then
        call status%add(prefix//'cannot read the connectivity of element block '''// &
            trim(block_names(b))//''' (ex_get_conn failed)')
        return
      end if
      do k = 1, n_in_block
        conn_all(:, e + k) = conn(8 * (k - 1) + 1:8 * k)
        zone_of_block(e + k) = b
        if (any(conn(8 * (k - 1) + 1:8 * k) < 1 .or. conn(8 * (k - 1) + 1:8 * k) > nnode)) &
            bad_node = .true.
      end do
      e = e + n_in_block
      deallocate(conn)
    end do
    if (bad_node) call status%add(prefix//'an element refers to a node outside 1..'//itoa(nnode))
    if (status%count > count0) return
    if (e /= nelem) then
      call status%add(prefix//'the element blocks hold '//itoa(e)//' elements, the file '// &
          'says '//itoa(nelem))
      return
    end if

    ! Nodes used by the hexahedra, in file order.
    allocate(new_id(nnode))
    new_id = 0
    do z = 1, nelem
      new_id(conn_all(:, z)) = 1
    end do
    n = 0
    do k = 1, nnode
      if (new_id(k) == 0) cycle
      n = n + 1
      new_id(k) = n
    end do
    mesh%nnode = n
    mesh%nzone = nelem
    allocate(mesh%coordinates(3, n), mesh%connectivity(8, nelem), mesh%zone_block(nelem))
    do k = 1, nnode
      if (new_id(k) > 0) mesh%coordinates(:, new_id(k)) = [real(xc(k), rk), real(yc(k), rk), &
          real(zc(k), rk)]
    end do
    nbad = 0
    do z = 1, nelem
      mesh%connectivity(:, z) = int(new_id(conn_all(:, z)), ik)
      mesh%zone_block(z) = int(zone_of_block(z), ik)
      if (.not. hex_volume(mesh%coordinates(:, mesh%connectivity(:, z))) > 0.0_rk) &
          call status%add_capped(nbad, MAX_REPORT, prefix//'element '//itoa(z)//' of block '''// &
          trim(block_names(zone_of_block(z)))//''' has a volume <= 0 (nodes not in the '// &
          'Exodus HEX8 order, or a degenerate element)')
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'elements with a volume <= 0')

    ! Side sets.
    allocate(mesh%set_start(nsideset + 1))
    mesh%set_start(1) = 1
    allocate(mesh%set_zone(0), mesh%set_face(0))
    allocate(set_names(nsideset))
    mesh%nset = nsideset
    if (nsideset > 0) then
      deallocate(ids)
      allocate(ids(nsideset))
      if (exo_ids(exoid, KIND_SIDE_SET, ids) /= 0) then
        call status%add(prefix//'cannot read the side set ids (ex_get_ids failed)')
        return
      end if
      call entity_names(exoid, KIND_SIDE_SET, ids, 'sideset_', 'side set', prefix, set_names, &
          status)
    end if
    do s = 1, nsideset
      if (exo_side_set_size(exoid, ids(s), nside) /= 0) then
        call status%add(prefix//'cannot read side set '''//trim(set_names(s))// &
            ''' (ex_get_set_param failed)')
        return
      end if
      allocate(elem(max(nside, 1)), side(max(nside, 1)))
      if (nside > 0) then
        if (exo_side_set(exoid, ids(s), elem, side) /= 0) then
          call status%add(prefix//'cannot read side set '''//trim(set_names(s))// &
              ''' (ex_get_set failed)')
          return
        end if
      end if
      nface = mesh%set_start(s) - 1
      mesh%set_zone = [mesh%set_zone, int(elem(:nside), ik)]
      mesh%set_face = [mesh%set_face, int(side(:nside), ik)]
      nbad = 0
      do k = nface + 1, nface + nside
        if (mesh%set_zone(k) < 1 .or. mesh%set_zone(k) > nelem .or. mesh%set_face(k) < 1 .or. &
            mesh%set_face(k) > 6) then
          call status%add_capped(nbad, MAX_REPORT, prefix//'side set '''//trim(set_names(s))//''': entry '// &
              itoa(k - nface)//' names element '//itoa(int(mesh%set_zone(k)))//', side '// &
              itoa(int(mesh%set_face(k)))//' (elements are 1..'//itoa(nelem)// &
              ', sides of a HEX8 1..6)')
        else
          mesh%set_face(k) = int(EXODUS_SIDE_FACE(mesh%set_face(k)), ik)
        end if
      end do
      call status%add_more(prefix, nbad, MAX_REPORT, 'bad entries of side set '''// &
          trim(set_names(s))//'''')
      mesh%set_start(s + 1) = nface + nside + 1
      deallocate(elem, side)
    end do
    call move_alloc(set_names, mesh%set_name)
  end subroutine read_mesh

  !> Names of the blocks or sets ids: the file's, else default_prefix<id>;
  !> each at most NAME_LEN characters and different from the others.
  subroutine entity_names(exoid, kind, ids, default_prefix, what, prefix, names, status)
    integer(c_int), intent(in) :: exoid, kind, ids(:)
    character(len=*), intent(in) :: default_prefix, what, prefix
    character(len=NAME_LEN), intent(out) :: names(:)
    type(status_t), intent(inout) :: status
    character(len=TEXT_LEN) :: text
    integer :: i, j
    do i = 1, size(ids)
      text = ''
      if (exo_name(exoid, kind, ids(i), text, len(text, c_int)) /= 0) text = ''
      text = c_text(text)
      if (len_trim(text) == 0) text = default_prefix//itoa(int(ids(i)))
      if (len_trim(text) > NAME_LEN) call status%add(prefix//'the name '''//trim(text)// &
          ''' of '//what//' '//itoa(int(ids(i)))//' is longer than '//itoa(NAME_LEN)// &
          ' characters')
      if (scan(trim(text), ' ,') > 0) call status%add(prefix//'the name '''//trim(text)// &
          ''' of '//what//' '//itoa(int(ids(i)))//' contains a blank or a comma (deck lists '// &
          'of names are separated by them); rename it in the meshing tool')
      names(i) = text(1:NAME_LEN)
      do j = 1, i - 1
        if (names(j) == names(i)) call status%add(prefix//what//'s '//itoa(int(ids(j)))// &
            ' and '//itoa(int(ids(i)))//' have the same name '''//trim(names(i))//'''')
      end do
    end do
  end subroutine entity_names

  !> An 8-node hexahedron by its Exodus type name.
  logical function is_hex8(type_text, nper)
    character(len=*), intent(in) :: type_text
    integer, intent(in) :: nper
    character(len=len(type_text)) :: upper
    integer :: i, c
    upper = type_text
    do i = 1, len(upper)
      c = iachar(upper(i:i))
      if (c >= iachar('a') .and. c <= iachar('z')) upper(i:i) = achar(c - 32)
    end do
    is_hex8 = nper == 8 .and. (trim(upper) == 'HEX8' .or. trim(upper) == 'HEX' .or. &
        trim(upper) == 'HEXAHEDRON')
  end function is_hex8

  !> A C string (up to its NUL) as blank-padded Fortran text.
  pure function c_text(text) result(clean)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: clean
    integer :: k
    k = index(text, c_null_char)
    clean = text
    if (k > 0) clean = text(1:k - 1)
  end function c_text

  ! ---------------------------------------------------------------------------
  ! Read by ranges: every rank reads its own part of the file
  ! ---------------------------------------------------------------------------

  !> First pass of a read by ranges (collective): every rank reads the sizes,
  !> names and element types (small), checks the coordinates of its block of
  !> the file's nodes and the connectivity of its block of the elements, in
  !> reads of at most CHUNK items, and tells the nodes' owners which nodes the
  !> hexahedra use; the owners number them. Every rank ends with the same
  !> problems in status (messages starting "mesh file '<path>': ").
  subroutine exodus_scan(path, part, status)
    character(len=*), intent(in) :: path !< the Exodus II file (full path)
    type(exodus_part_t), intent(out) :: part
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: prefix
    logical :: exists
    integer(c_int) :: exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset
    real(c_float) :: version
    integer :: fail

    part%path = path
    prefix = "mesh file '"//trim(path)//"': "
    allocate(part%block_names(0), part%set_names(0))
    inquire(file=path, exist=exists)
    if (par_max(merge(0, 1, exists)) > 0) then
      call status%add(prefix//'no such file')
      return
    end if
    fail = 0
    if (exo_open(trim(path)//c_null_char, exoid, version) /= 0) fail = 1
    if (par_max(fail) > 0) then
      call status%add(prefix//'cannot open it as an Exodus II file (the Exodus II library '// &
          'could not read it: not a netCDF file, or damaged)')
      if (fail == 0) fail = exo_close(exoid)
      return
    end if
    if (exo_init(exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset) /= 0) fail = 1
    if (par_max(fail) > 0) then
      call status%add(prefix//'cannot read its sizes (ex_get_init failed)')
    else if (ndim /= 3) then
      call status%add(prefix//'the mesh is '//itoa(int(ndim))//'D; impact3d reads 3D meshes')
    else if (nblock < 1 .or. nelem < 1) then
      call status%add(prefix//'the file has no element block (no elements)')
    else
      part%nnode_file = int(nnode)
      part%nelem = int(nelem)
      part%nblock = int(nblock)
      part%nset = int(nsideset)
      call scan_file(exoid, prefix, part, status)
    end if
    if (par_max(merge(1, 0, exo_close(exoid) /= 0)) > 0) call status%add(prefix// &
        'cannot close it (ex_close failed)')
  end subroutine exodus_scan

  !> exodus_scan after the sizes.
  subroutine scan_file(exoid, prefix, part, status)
    integer(c_int), intent(in) :: exoid
    character(len=*), intent(in) :: prefix
    type(exodus_part_t), intent(inout) :: part
    type(status_t), intent(inout) :: status
    real(c_double), allocatable :: xc(:), yc(:), zc(:)
    integer(c_int), allocatable :: conn(:, :)
    integer(c_int) :: n_in_block, nper, nside
    integer(i8), allocatable :: ids(:), send(:, :), recv(:, :)
    integer, allocatable :: dest(:)
    character(len=TEXT_LEN) :: type_text
    character(len=LINE_LEN), allocatable :: lines(:)
    integer(i8) :: efirst, first, nused, before
    integer :: b, i, n, ne, nbad, count0, s, round, rounds, fail, bad_node
    count0 = status%count

    ! Coordinates of this rank's block of nodes: all finite.
    call par_block_range(int(part%nnode_file, i8), par_size(), par_rank(), part%node_first, &
        part%node_count)
    allocate(xc(min(CHUNK, part%node_count)), yc(min(CHUNK, part%node_count)), &
        zc(min(CHUNK, part%node_count)), lines(MAX_REPORT))
    nbad = 0
    fail = 0
    do i = 0, part%node_count - 1, CHUNK
      n = min(CHUNK, part%node_count - i)
      if (exo_partial_coord(exoid, int(part%node_first) + i, n, xc, yc, zc) /= 0) then
        fail = 1
        exit
      end if
      do b = 1, n
        if (ieee_is_finite(xc(b)) .and. ieee_is_finite(yc(b)) .and. ieee_is_finite(zc(b))) cycle
        nbad = nbad + 1
        if (nbad <= MAX_REPORT) lines(nbad) = prefix//'node '//itoa(int(part%node_first) + i + &
            b - 1)//' has a coordinate that is not a finite number'
      end do
    end do
    deallocate(xc, yc, zc)
    if (par_max(fail) > 0) then
      call status%add(prefix//'cannot read the node coordinates (ex_get_coord failed)')
      return
    end if
    call merge_capped(status, prefix, lines, nbad, 'nodes with non-finite coordinates')

    ! Element blocks: ids, names, types and sizes (every rank the same).
    allocate(part%block_id(part%nblock), part%block_start(part%nblock + 1))
    deallocate(part%block_names)
    allocate(part%block_names(part%nblock))
    part%block_start = 0
    if (exo_ids(exoid, KIND_BLOCK, part%block_id) /= 0) then
      call status%add(prefix//'cannot read the element block ids (ex_get_ids failed)')
      return
    end if
    call entity_names(exoid, KIND_BLOCK, part%block_id, 'block_', 'element block', prefix, &
        part%block_names, status)
    do b = 1, part%nblock
      part%block_start(b + 1) = part%block_start(b)
      if (exo_block(exoid, part%block_id(b), type_text, len(type_text, c_int), n_in_block, &
          nper) /= 0) then
        call status%add(prefix//'cannot read element block '''//trim(part%block_names(b))// &
            ''' (id '//itoa(int(part%block_id(b)))//'): ex_get_block failed')
        return
      end if
      type_text = c_text(type_text)
      if (.not. is_hex8(type_text, int(nper))) then
        call status%add(prefix//'element block '''//trim(part%block_names(b))//''' (id '// &
            itoa(int(part%block_id(b)))//') holds '//itoa(int(n_in_block))// &
            ' elements of type '''//trim(type_text)//''' with '//itoa(int(nper))// &
            ' nodes; impact3d reads 8-node hexahedra (HEX8) only')
        cycle
      end if
      if (part%block_start(b) + n_in_block > part%nelem) then
        call status%add(prefix//'the element blocks hold more elements than the file''s '// &
            'element count '//itoa(part%nelem))
        return
      end if
      part%block_start(b + 1) = part%block_start(b) + int(n_in_block)
    end do
    if (status%count > count0) return
    if (part%block_start(part%nblock + 1) /= part%nelem) then
      call status%add(prefix//'the element blocks hold '//itoa(part%block_start(part%nblock + &
          1))//' elements, the file says '//itoa(part%nelem))
      return
    end if

    ! Side sets: ids, names, sizes (the entries are read by range_add_exodus).
    allocate(part%set_id(part%nset), part%set_size(part%nset))
    deallocate(part%set_names)
    allocate(part%set_names(part%nset))
    if (part%nset > 0) then
      if (exo_ids(exoid, KIND_SIDE_SET, part%set_id) /= 0) then
        call status%add(prefix//'cannot read the side set ids (ex_get_ids failed)')
        return
      end if
      call entity_names(exoid, KIND_SIDE_SET, part%set_id, 'sideset_', 'side set', prefix, &
          part%set_names, status)
    end if
    do s = 1, part%nset
      if (exo_side_set_size(exoid, part%set_id(s), nside) /= 0) then
        call status%add(prefix//'cannot read side set '''//trim(part%set_names(s))// &
            ''' (ex_get_set_param failed)')
        return
      end if
      part%set_size(s) = int(nside, i8)
    end do

    ! This rank's block of elements, CHUNK at a time: node numbers in range;
    ! the nodes used go to the owners of their block of the file's nodes.
    allocate(part%node_id(part%node_count))
    part%node_id = 0
    call par_block_range(int(part%nelem, i8), par_size(), par_rank(), efirst, ne)
    rounds = par_route_rounds(int(ne, i8), CHUNK)
    allocate(conn(8, min(CHUNK, ne)))
    fail = 0
    bad_node = 0
    do round = 1, rounds
      first = efirst + int(round - 1, i8) * CHUNK
      n = int(max(0_i8, min(int(CHUNK, i8), efirst + ne - first)))
      if (n > 0 .and. fail == 0) then
        if (.not. read_conn(exoid, part, int(first), n, conn)) fail = 1
      end if
      if (fail /= 0) n = 0
      ids = reshape(int(conn(:, :n), i8), [8 * n])
      if (any(ids < 1 .or. ids > part%nnode_file)) bad_node = 1
      ids = pack(ids, ids >= 1 .and. ids <= part%nnode_file)
      call sort_unique(ids)
      allocate(send(1, size(ids)), dest(size(ids)))
      send(1, :) = ids
      do i = 1, size(ids)
        dest(i) = par_block_owner(int(part%nnode_file, i8), par_size(), ids(i))
      end do
      call par_route_free(send, dest, recv)
      deallocate(dest)
      do i = 1, size(recv, 2)
        part%node_id(recv(1, i) - part%node_first + 1) = 1
      end do
    end do
    deallocate(conn)
    if (par_max(fail) > 0) call status%add(prefix//'cannot read the connectivity of the '// &
        'element blocks (ex_get_partial_conn failed)')
    if (par_max(bad_node) > 0) call status%add(prefix//'an element refers to a node outside 1..'// &
        itoa(part%nnode_file))
    if (status%count > count0) return

    ! The used nodes numbered in file order: this rank's after the earlier ranks'.
    nused = count(part%node_id > 0)
    before = par_exscan_i8(nused)
    part%nnode = par_sum(nused)
    nused = 0
    do i = 1, part%node_count
      if (part%node_id(i) == 0) cycle
      nused = nused + 1
      part%node_id(i) = before + nused
    end do
  end subroutine scan_file

  !> Connectivity of the elements first .. first + n - 1 (file order, block
  !> after block) into conn; false if the library fails.
  logical function read_conn(exoid, part, first, n, conn) result(ok)
    integer(c_int), intent(in) :: exoid
    type(exodus_part_t), intent(in) :: part
    integer, intent(in) :: first, n
    integer(c_int), intent(inout) :: conn(:, :) !< (8, >= n)
    integer :: b, lo, hi
    ok = .true.
    do b = 1, part%nblock
      lo = max(first, part%block_start(b) + 1)
      hi = min(first + n - 1, part%block_start(b + 1))
      if (hi < lo) cycle
      if (exo_partial_conn(exoid, part%block_id(b), lo - part%block_start(b), hi - lo + 1, &
          conn(:, lo - first + 1:hi - first + 1)) /= 0) ok = .false.
    end do
  end function read_conn

  !> Element block of element e.
  pure integer function block_of(part, e) result(b)
    type(exodus_part_t), intent(in) :: part
    integer, intent(in) :: e
    do b = 1, part%nblock
      if (e <= part%block_start(b + 1)) return
    end do
    b = part%nblock
  end function block_of

  !> Second pass (collective): the part's elements that lie in this rank's
  !> range (global zone ids zone0 + 1 ..) with their node ids (node0 + the
  !> file-order ids), corner positions (bit for bit the file's doubles) and
  !> element block (zone_block = the block's index in part%block_names), read
  !> CHUNK elements at a time; the corners come from the nodes' owners in one
  !> request/answer. Side set entries are read by ranges and sent to the
  !> ranks of their zones, as range_add_global adds them. summary: the part's
  !> lines as mesh_import_summary writes them (sums taken in the order a
  !> single reader takes them, so bitwise the same on any rank count). lo..hi
  !> are the range positions filled.
  subroutine range_add_exodus(range, part, zone0, node0, sets, ord0, lo, hi, title, summary, &
      status)
    type(mesh_range_t), intent(inout) :: range
    type(exodus_part_t), intent(in) :: part
    integer(i8), intent(in) :: zone0, node0
    integer, intent(in) :: sets(:, :) !< (2, part%nset)
    integer(i8), intent(in) :: ord0(:, :) !< (2, part%nset)
    integer, intent(out) :: lo, hi
    character(len=*), intent(in) :: title !< first line of the summary
    character(len=200), allocatable, intent(out) :: summary(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: prefix
    character(len=LINE_LEN), allocatable :: lines(:)
    integer(c_int) :: exoid
    real(c_float) :: version
    integer(c_int), allocatable :: conn(:, :), elem(:), side(:)
    integer(i8), allocatable :: ids(:), send(:, :), recv(:, :), answer(:, :), key(:)
    integer, allocatable :: dest(:), source(:), order(:)
    real(rk), allocatable :: value(:, :), volume(:), vol(:)
    real(rk) :: total(4), p(3, 4), a
    integer(i8) :: zfirst, zlast, g, first, efirst
    integer :: nz, i, j, k, c, z, n, fail, nbad, round, rounds, s, m, pos, ne, b, nline

    prefix = "mesh file '"//trim(part%path)//"': "
    zfirst = max(zone0 + 1, range%first)
    zlast = min(zone0 + part%nelem, range%first + range%nzone - 1)
    lo = int(zfirst - range%first) + 1
    hi = int(zlast - range%first) + 1
    nz = max(0, hi - lo + 1)
    fail = 0
    if (exo_open(trim(part%path)//c_null_char, exoid, version) /= 0) fail = 1
    if (par_max(fail) > 0) then
      call status%add(prefix//'cannot open it as an Exodus II file (the Exodus II library '// &
          'could not read it: not a netCDF file, or damaged)')
      if (fail == 0) fail = exo_close(exoid)
      allocate(summary(0))
      return
    end if

    ! This rank's elements, CHUNK at a time, straight into the range.
    allocate(conn(8, min(CHUNK, nz)))
    do i = 0, nz - 1, CHUNK
      n = min(CHUNK, nz - i)
      if (.not. read_conn(exoid, part, int(zfirst - zone0) + i, n, conn)) fail = 1
      do k = 1, n
        z = int(zfirst - zone0) + i + k - 1
        range%conn(:, lo + i + k - 1) = int(conn(:, k), i8)
        range%zone_block(lo + i + k - 1) = int(block_of(part, z), ik)
      end do
    end do
    deallocate(conn)
    if (par_max(fail) > 0) then
      call status%add(prefix//'cannot read the connectivity of the element blocks '// &
          '(ex_get_partial_conn failed)')
      fail = exo_close(exoid)
      allocate(summary(0))
      return
    end if

    ! The nodes' ids and positions from the owners of their blocks: each
    ! owner reads its file nodes CHUNK at a time and answers
    ! [file node, id, x, y, z].
    ids = reshape(range%conn(:, lo:lo + nz - 1), [8 * nz])
    call sort_unique(ids)
    allocate(send(1, size(ids)), dest(size(ids)))
    send(1, :) = ids
    do i = 1, size(ids)
      dest(i) = par_block_owner(int(part%nnode_file, i8), par_size(), ids(i))
    end do
    call par_route_free(send, dest, recv, source)
    deallocate(dest)
    call sort_order(recv(1, :), order)
    allocate(answer(5, size(recv, 2)))
    j = 1
    do first = part%node_first, part%node_first + part%node_count - 1, CHUNK
      if (j > size(order)) exit
      n = int(min(int(CHUNK, i8), part%node_first + part%node_count - first))
      if (recv(1, order(j)) >= first + n) cycle
      block
        real(c_double) :: x(n), y(n), zz(n)
        if (exo_partial_coord(exoid, int(first), n, x, y, zz) /= 0) fail = 1
        do while (j <= size(order))
          k = order(j)
          if (recv(1, k) >= first + n) exit
          m = int(recv(1, k) - first) + 1
          answer(:, k) = [recv(1, k), part%node_id(recv(1, k) - part%node_first + 1), &
              transfer(real(x(m), rk), 1_i8), transfer(real(y(m), rk), 1_i8), &
              transfer(real(zz(m), rk), 1_i8)]
          j = j + 1
        end do
      end block
    end do
    deallocate(recv, order)
    call par_route_free(answer, source, recv)
    deallocate(source)
    if (par_max(fail) > 0) then
      call status%add(prefix//'cannot read the node coordinates (ex_get_coord failed)')
      fail = exo_close(exoid)
      allocate(summary(0))
      return
    end if
    ! (answers come grouped by owner, each in the order asked: ids's order)
    if (any(recv(1, :) /= ids)) error stop 'range_add_exodus: answers out of order'
    do i = 1, nz
      do c = 1, 8
        k = sorted_find(ids, range%conn(c, lo + i - 1))
        range%conn(c, lo + i - 1) = node0 + recv(2, k)
        do j = 1, 3
          range%corner_x(j, c, lo + i - 1) = transfer(recv(2 + j, k), 1.0_rk)
        end do
      end do
    end do
    deallocate(recv, ids)

    ! Orientation: Exodus and impact3d share the node order.
    allocate(lines(MAX_REPORT), vol(nz))
    nbad = 0
    do i = 1, nz
      z = int(zfirst - zone0) + i - 1
      vol(i) = hex_volume(range%corner_x(:, :, lo + i - 1))
      if (.not. vol(i) > 0.0_rk) then
        nbad = nbad + 1
        if (nbad <= MAX_REPORT) lines(nbad) = prefix//'element '//itoa(z)//' of block '''// &
            trim(part%block_names(range%zone_block(lo + i - 1)))//''' has a volume <= 0 '// &
            '(nodes not in the Exodus HEX8 order, or a degenerate element)'
      end if
    end do
    call merge_capped(status, prefix, lines, nbad, 'elements with a volume <= 0')

    ! Volumes per block, summed in zone order.
    allocate(volume(part%nblock))
    do b = 1, part%nblock
      key = pack([(zfirst - zone0 + i - 1, i = 1, nz)], range%zone_block(lo:lo + nz - 1) == b)
      value = reshape(pack(vol, range%zone_block(lo:lo + nz - 1) == b), [1, size(key)])
      call par_ordered_sum(key, value, total(1:1))
      volume(b) = total(1)
    end do
    deallocate(key, value)
    allocate(summary(2 + part%nblock + part%nset))
    summary(1) = title
    write(summary(2), '(a,i0,a,i0,a,es24.16)') '  ', part%nnode, ' nodes, ', part%nelem, &
        ' zones, volume ', sum(volume)
    nline = 2
    do b = 1, part%nblock
      nline = nline + 1
      write(summary(nline), '(3a,i0,a,es24.16)') '  block ''', trim(part%block_names(b)), &
          ''': ', part%block_start(b + 1) - part%block_start(b), ' zones, volume ', volume(b)
    end do

    ! Side sets, each read by ranges: [global zone, face, set, place in the set]
    ! to the zone's rank.
    do s = 1, part%nset
      call par_block_range(part%set_size(s), par_size(), par_rank(), efirst, ne)
      rounds = par_route_rounds(int(ne, i8), CHUNK)
      allocate(elem(max(1, min(CHUNK, ne))), side(max(1, min(CHUNK, ne))))
      allocate(key(0), value(4, 0))
      nbad = 0
      do round = 1, rounds
        first = efirst + int(round - 1, i8) * CHUNK
        n = int(max(0_i8, min(int(CHUNK, i8), efirst + ne - first)))
        if (n > 0 .and. fail == 0) then
          if (exo_partial_side_set(exoid, part%set_id(s), int(first), n, elem, side) /= 0) &
              fail = 1
        end if
        if (fail /= 0) n = 0
        allocate(send(4, n), dest(n))
        m = 0
        do i = 1, n
          if (elem(i) < 1 .or. elem(i) > part%nelem .or. side(i) < 1 .or. side(i) > 6) then
            nbad = nbad + 1
            if (nbad <= MAX_REPORT) lines(nbad) = prefix//'side set '''// &
                trim(part%set_names(s))//''': entry '//itoa(int(first) + i - 1)// &
                ' names element '//itoa(int(elem(i)))//', side '//itoa(int(side(i)))// &
                ' (elements are 1..'//itoa(part%nelem)//', sides of a HEX8 1..6)'
            cycle
          end if
          m = m + 1
          g = zone0 + elem(i)
          send(:, m) = [g, int(EXODUS_SIDE_FACE(side(i)), i8), int(s, i8), first + i - 1]
          dest(m) = par_block_owner(range%nzone_global, par_size(), g)
        end do
        send = send(:, :m)
        call par_route_free(send, dest(:m), recv)
        deallocate(dest)
        call range_grow_faces(range, count(sets(:, s) > 0) * size(recv, 2))
        call grow_sums(key, value, size(recv, 2))
        pos = range%nface
        do i = 1, size(recv, 2)
          k = int(recv(1, i) - range%first) + 1
          do j = 1, 4
            p(:, j) = range%corner_x(:, HEX_FACE_NODES(j, recv(2, i)), k)
          end do
          a = norm2(quad_vector_area(p))
          key(size(key) - size(recv, 2) + i) = recv(4, i)
          value(:, size(key) - size(recv, 2) + i) = [a, a * 0.25_rk * sum(p, dim=2)]
          do c = 1, 2
            if (sets(c, s) == 0) cycle
            pos = pos + 1
            range%face_set(pos) = sets(c, s)
            range%face_zone(pos) = k
            range%face_face(pos) = int(recv(2, i))
            range%face_ord(pos) = ord0(c, s) + recv(4, i)
          end do
        end do
        range%nface = pos
      end do
      deallocate(elem, side)
      call merge_capped(status, prefix, lines, nbad, 'bad entries of side set '''// &
          trim(part%set_names(s))//'''')
      ! The area and centre, summed in the set's order as mesh_set_area sums.
      call par_ordered_sum(key, value, total)
      if (total(1) > 0.0_rk) total(2:4) = total(2:4) / total(1)
      nline = nline + 1
      write(summary(nline), '(3a,i0,a,es24.16,a,3es24.16)') '  face set ''', &
          trim(part%set_names(s)), ''': ', part%set_size(s), ' faces, area ', total(1), &
          ', centre', total(2:4)
      deallocate(key, value)
    end do
    if (par_max(fail) > 0) call status%add(prefix//'cannot read the side sets '// &
        '(ex_get_partial_side_set failed)')
    if (par_max(merge(1, 0, exo_close(exoid) /= 0)) > 0) call status%add(prefix// &
        'cannot close it (ex_close failed)')
  end subroutine range_add_exodus

  !> n more entries at the end of key and value.
  subroutine grow_sums(key, value, n)
    integer(i8), allocatable, intent(inout) :: key(:)
    real(rk), allocatable, intent(inout) :: value(:, :)
    integer, intent(in) :: n
    integer(i8), allocatable :: k2(:)
    real(rk), allocatable :: v2(:, :)
    allocate(k2(size(key) + n), v2(size(value, 1), size(key) + n))
    k2(:size(key)) = key
    v2(:, :size(key)) = value
    call move_alloc(k2, key)
    call move_alloc(v2, value)
  end subroutine grow_sums


end module mesh_exodus
